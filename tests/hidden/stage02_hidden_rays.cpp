// Hidden stage-02 cases (instructor-only: tools/kit_manifest.json keeps tests/hidden/ out
// of every student kit; tools/grade.py --hidden tests/hidden grades with them).
//
// generate_ray on its own: the ray generator is filled in by hand (the canonical frame,
// no make_frame and no window_from_fov), so only the "generate a ray" exercise is
// measured. Expected values by hand from Fundamentals of Computer Graphics, 4th ed.,
// sec. 4.3, eq. 4.1: u = l + (r - l) x / nx, v = b + (t - b) y / ny.
#include <doctest/doctest.h>

#include <rt/camera/camera.hpp>

namespace {

rt::ray_generator canonical(rt::projection kind)
{
    rt::ray_generator gen;
    gen.kind = kind;
    gen.e = rt::vec3(1, 2, 3);
    gen.basis = rt::frame{}; // u = x, v = y, w = z
    gen.plane = rt::window{-4, 4, -2, 2};
    gen.d = 2;
    gen.nx = 8;
    gen.ny = 4;
    return gen;
}

} // namespace

TEST_CASE("an orthographic ray starts on the image plane and looks along -w")
{
    // x = 6 of 8 pixels: u = -4 + 8 * 6/8 = 2; y = 1 of 4: v = -2 + 4 * 1/4 = -1
    const rt::ray r = rt::generate_ray(canonical(rt::projection::orthographic), 6, 1);
    CHECK(r.origin.x == doctest::Approx(1 + 2));
    CHECK(r.origin.y == doctest::Approx(2 - 1));
    CHECK(r.origin.z == doctest::Approx(3));
    CHECK(r.direction.x == doctest::Approx(0));
    CHECK(r.direction.y == doctest::Approx(0));
    CHECK(r.direction.z == doctest::Approx(-1));
}

TEST_CASE("a perspective ray starts at the eye and points at (u, v, -d)")
{
    // the image's top-right corner: u = r = 4, v = t = 2, d = 2
    const rt::ray r = rt::generate_ray(canonical(rt::projection::perspective), 8, 4);
    CHECK(r.origin.x == doctest::Approx(1));
    CHECK(r.origin.y == doctest::Approx(2));
    CHECK(r.origin.z == doctest::Approx(3));
    CHECK(r.direction.x == doctest::Approx(4));
    CHECK(r.direction.y == doctest::Approx(2));
    CHECK(r.direction.z == doctest::Approx(-2));
}
