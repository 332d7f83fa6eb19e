// Stage 07 - reflections: L += km raycolor(p, r), r = d - 2 (d.n) n
// (Fundamentals of Computer Graphics, 4th ed., sec. 4.8).
//
// The scenes here have no lights, only ambient light, so every color is a
// closed form (ka Ia, km ka Ia, a geometric series) and nothing of stage 05's
// or 06's exercises is called. Scenes and rays are built here.
#include "rt_doctest.hpp"

#include <cmath>
#include <cstdint>

#include <rt/bvh/accelerator.hpp>
#include <rt/shading/raytracer.hpp>
#include <rt/scene/scene.hpp>

namespace {

void check_color(const rt::color& got, double r, double g, double b, double eps = 1e-5)
{
    INFO("expected the color " << rt_doctest::text(rt::vec3(rt::real(r), rt::real(g), rt::real(b))) << ", found "
                                << rt_doctest::text(got));
    CHECK(got.r == doctest::Approx(r).epsilon(eps));
    CHECK(got.g == doctest::Approx(g).epsilon(eps));
    CHECK(got.b == doctest::Approx(b).epsilon(eps));
}

/// Two triangles making the square [-h, h]^2 in the plane z = z0 (normal +z).
void add_square_z(rt::scene& s, rt::real h, rt::real z0, int material)
{
    rt::triangle a, b;
    a.a = {-h, -h, z0};
    a.b = {h, -h, z0};
    a.c = {h, h, z0};
    b.a = {-h, -h, z0};
    b.b = {h, h, z0};
    b.c = {-h, h, z0};
    a.material = b.material = material;
    s.shapes.emplace_back(a);
    s.shapes.emplace_back(b);
}

/// The accelerator seen through a probe of the recursion: it counts the
/// closest-hit queries and, past `limit` of them, answers every query with a
/// miss. A ray_color without a depth cap between two facing mirrors would call
/// itself until the stack overflows (a crash that names nothing); through the
/// probe it ends after `limit` queries, and the count shows that it did not stop.
struct depth_probe {
    const rt::accelerator* accel;
    std::uint64_t* queries;
    std::uint64_t limit;

    bool closest_hit(const rt::ray& r, rt::real tmin, rt::real tmax, rt::hit_record& rec) const
    {
        if (++*queries > limit)
            return false;
        return accel->closest_hit(r, tmin, tmax, rec);
    }
    bool any_hit(const rt::ray& r, rt::real tmin, rt::real tmax) const { return accel->any_hit(r, tmin, tmax); }
};

/// How many queries the probe answers: far beyond 1 + the largest max_depth
/// here (64), far below what overflows a stack.
const std::uint64_t probe_limit = 300;

/// Whether the recursion stopped: a CHECK naming the depth cap when the probe
/// had to stop it.
bool stopped(std::uint64_t queries, int max_depth)
{
    CHECK_MESSAGE(queries <= probe_limit,
                  "expected the recursion to stop at max_depth = "
                      << max_depth << " (max_depth + 1 = " << max_depth + 1
                      << " closest-hit queries: the camera ray and a reflection at each depth 1 to max_depth), found "
                         "it still going after "
                      << probe_limit << " queries (the test then answered every query with a miss, where the "
                      "recursion would have gone on until the stack overflowed): no depth cap. Trace a reflection "
                      "only while depth < s.max_depth, and give the reflected ray depth + 1");
    return queries <= probe_limit;
}

rt::material ambient_material(rt::color ka, rt::color km = rt::color(0.0f))
{
    rt::material m;
    m.ka = ka;
    m.kd = rt::color(0.0f);
    m.ks = rt::color(0.0f);
    m.km = km;
    return m;
}

} // namespace

TEST_CASE("reflect: same length, angle in equals angle out, twice is the identity")
{
    const rt::vec3 n = glm::normalize(rt::vec3(1, 2, -0.5f));
    const rt::vec3 ds[] = {{1, 0, 0}, {-0.3f, -2, 1}, {0, 0, 5}, {2, 4, -1}};
    for (const rt::vec3& d : ds) {
        const rt::vec3 r = rt::reflect(d, n);
        INFO("reflect(" << rt_doctest::text(d) << ", n = " << rt_doctest::text(n) << ") = " << rt_doctest::text(r)
             << ": expected r = d - 2 (d.n) n (FCG 4th ed., sec. 4.8), the same length as d, its normal part "
                "flipped, its tangential part kept, and reflect(r, n) = d");
        CHECK(glm::length(r) == doctest::Approx(glm::length(d)));
        CHECK(glm::dot(r, n) == doctest::Approx(-glm::dot(d, n)));
        // the tangential part is kept
        const rt::vec3 tangential_d = d - glm::dot(d, n) * n, tangential_r = r - glm::dot(r, n) * n;
        CHECK_MESSAGE(glm::length(tangential_d - tangential_r) < 1e-5,
                      "expected the tangential part d - (d.n) n = " << tangential_d << " kept, found "
                                                                    << tangential_r);
        const rt::vec3 back = rt::reflect(r, n);
        CHECK_MESSAGE(glm::length(back - d) < 1e-5, "expected reflect(r, n) = d = " << d << ", found " << back);
    }
    // straight down onto a floor comes straight back up
    const rt::vec3 up = rt::reflect({0, -3, 0}, {0, 1, 0});
    INFO("straight down onto a floor, (0, -3, 0) with n = (0, 1, 0): expected (0, 3, 0), found " << rt_doctest::text(up));
    CHECK(up.x == doctest::Approx(0));
    CHECK(up.y == doctest::Approx(3));
}

TEST_CASE("a mirror shows km times the color of what it reflects")
{
    rt::scene s;
    s.ambient = rt::color(1.0f);
    s.background = {0.1f, 0.2f, 0.3f};
    s.materials.push_back(ambient_material(rt::color(0.0f), {0.5f, 0.6f, 0.7f})); // 0: a pure mirror
    s.materials.push_back(ambient_material({0.2f, 0.4f, 0.8f}));                 // 1: a matte ball
    add_square_z(s, 10, 0, 0);                                                   // mirror floor z = 0
    rt::sphere ball;
    ball.center = {0, 0, 5};
    ball.radius = 1;
    ball.material = 1;
    s.shapes.emplace_back(ball);
    const rt::accelerator accel(s);

    // A ray from (4, 0, 4) to the mirror point (2, 0, 0) reflects to (0, 0, 4),
    // the bottom of the ball: L = mirror ambient (0) + km * ka_ball * Ia.
    const rt::ray r{rt::vec3(4, 0, 4), rt::vec3(-2, 0, -4)};
    {
        INFO("the ray from (4, 0, 4) meets the mirror floor (ka 0, km (0.5, 0.6, 0.7)) at (2, 0, 0) and reflects to "
             "the bottom of the ball (ka (0.2, 0.4, 0.8)): expected km ka_ball Ia");
        check_color(rt::ray_color(s, accel, r), 0.5 * 0.2, 0.6 * 0.4, 0.7 * 0.8);
    }
    {
        INFO("the ball seen directly (not a mirror): expected its own ambient color ka Ia, nothing reflected");
        check_color(rt::ray_color(s, accel, rt::ray{rt::vec3(0, 0, 20), rt::vec3(0, 0, -1)}), 0.2, 0.4, 0.8);
    }
    {
        INFO("the ray meets the mirror floor at (9.1, 9.1, 0) and its reflection misses everything: expected km times "
             "the background (0.1, 0.2, 0.3)");
        check_color(rt::ray_color(s, accel, rt::ray{rt::vec3(9, 9, 1), rt::vec3(0.1f, 0.1f, -1)}), 0.05, 0.12, 0.21);
    }
    // With max_depth 0 there is no reflection at all.
    s.max_depth = 0;
    INFO("max_depth 0: the camera ray is at depth 0 and no reflection is traced, so the mirror shows only its own "
         "ka Ia = 0; a color here means a reflection was traced: trace one only while depth < s.max_depth");
    check_color(rt::ray_color(s, accel, r), 0, 0, 0);
}

TEST_CASE("two facing mirrors: recursion stops at max_depth with a bounded geometric sum")
{
    // Mirrors z = 0 (facing +z) and z = 2 (facing -z), each with ambient a and
    // mirror reflectance k. A ray along the z axis bounces forever in theory; with
    // depth limit D it sees a (1 + k + ... + k^D) = a (1 - k^(D+1)) / (1 - k) < a / (1 - k).
    const double a = 0.1, k = 0.9;
    for (int D : {0, 1, 5, 20, 64}) {
        rt::scene s;
        s.ambient = rt::color(1.0f);
        s.max_depth = D;
        s.materials.push_back(ambient_material(rt::color(float(a)), rt::color(float(k))));
        add_square_z(s, 5, 0, 0);
        add_square_z(s, 5, 2, 0);
        const rt::accelerator accel(s);
        std::uint64_t queries = 0;
        const rt::color L = rt::ray_color(s, depth_probe{&accel, &queries, probe_limit},
                                          rt::ray{rt::vec3(0.1f, 0.2f, 1), rt::vec3(0, 0, -1)});
        const double expected = a * (1 - std::pow(k, D + 1)) / (1 - k);
        CAPTURE(D);
        if (!stopped(queries, D))
            return; // the colors of a recursion the test cut short say nothing more
        INFO("two facing mirrors (ka = 0.1, km = 0.9), max_depth D: expected the camera ray and D reflections, "
             "a (1 + k + ... + k^D) = " << expected << "; more light means more reflections (trace one only while "
             "depth < s.max_depth, and give the reflected ray depth + 1), less means fewer");
        check_color(L, expected, expected, expected, 1e-4);
        CHECK_MESSAGE(double(L.r) < a / (1 - k), "expected less than the infinite sum a / (1 - k) = " << a / (1 - k)
                                                                                                      << ", found "
                                                                                                      << L.r);
    }
}

TEST_CASE("a mirror ball reflects the background where its reflections escape")
{
    rt::scene s;
    s.background = {0.25f, 0.5f, 1.0f};
    s.ambient = rt::color(0.0f);
    s.materials.push_back(ambient_material(rt::color(0.0f), rt::color(0.8f)));
    rt::sphere ball;
    ball.material = 0;
    s.shapes.emplace_back(ball);
    const rt::accelerator accel(s);
    // a ray hitting the front of the ball comes back out: 0.8 * background
    INFO("expected km * background = 0.8 * (0.25, 0.5, 1): the reflected ray leaves the ball and sees the sky; "
         "a darker color (0.8^k * background) means the reflected ray hit the ball again: "
         "start it off the surface (rt::spawn_ray), not at the hit point");
    check_color(rt::ray_color(s, accel, rt::ray{rt::vec3(0.3f, 0.4f, 5), rt::vec3(0, 0, -1)}), 0.2, 0.4, 0.8);
    // a miss is the background itself
    check_color(rt::ray_color(s, accel, rt::ray{rt::vec3(3, 0, 5), rt::vec3(0, 0, -1)}), 0.25, 0.5, 1.0);
}

TEST_CASE("two facing mirrors: exactly 1 + max_depth closest-hit queries")
{
    // The same mirrors, seen through depth_probe, which counts every query: the
    // camera ray and D reflections, D + 1 in all.
    // No light, so no shadow ray: a lit scene would also run stages 05 and 06,
    // and this suite grades stage 07 alone.
    for (int D : {0, 1, 5, 20}) {
        rt::scene s;
        s.max_depth = D;
        s.materials.push_back(ambient_material(rt::color(0.1f), rt::color(0.9f)));
        add_square_z(s, 5, 0, 0);
        add_square_z(s, 5, 2, 0);
        const rt::accelerator accel(s);
        std::uint64_t queries = 0;
        rt::ray_color(s, depth_probe{&accel, &queries, probe_limit}, rt::ray{rt::vec3(0.1f, 0.2f, 1), rt::vec3(0, 0, -1)});
        CAPTURE(D);
        if (!stopped(queries, D))
            return;
        CHECK_MESSAGE(queries == std::uint64_t(D + 1),
                      "expected max_depth + 1 = " << D + 1 << " closest-hit queries (the camera ray at depth 0 and a "
                      "reflection at each depth 1 to max_depth), found " << queries
                                                  << ": trace a reflection only while depth < s.max_depth, and give "
                                                     "the reflected ray depth + 1");
    }
}

TEST_CASE("a mirror ball far from the origin reflects only the sky: no speckles of its own surface (the reflected ray starts off the surface)")
{
    // A mirror ball (ka = 0, km = 0.5) alone under a sky: every ray that hits it
    // reflects away from it (the reflected ray leaves a convex surface) and sees
    // the sky, so each such pixel is exactly km times the background. A reflected
    // ray started at the computed hit point itself, which lies a rounding error
    // inside or outside the surface, finds the ball again at t ~ 0 for some rays
    // (Pharr, Jakob, Humphreys, PBR 3rd ed., sec. 3.9.5): a speckle. The ball is
    // placed where its coordinates are large, where the rounding shows.
    const rt::color km(0.5f), sky(0.2f, 0.4f, 0.8f);
    int speckles_total = 0;
    for (const double scale : {1.0, 1e2, 1e4}) {
        rt::scene s;
        s.ambient = rt::color(1.0f);
        s.background = sky;
        s.max_depth = 5;
        s.materials.push_back(ambient_material(rt::color(0.0f), km));
        rt::sphere ball;
        ball.center = rt::real(scale) * rt::vec3(0.6f, -0.48f, 0.64f) * rt::real(3);
        ball.radius = rt::real(scale);
        ball.material = 0;
        s.shapes.emplace_back(ball);
        const rt::accelerator accel(s);
        const rt::vec3 eye = ball.center + rt::vec3(0, 0, rt::real(4 * scale));
        int rays = 0, speckles = 0;
        const int n = 40;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                // aim at the visible cap, within 0.9 R of the axis
                const rt::real u = rt::real(0.9) * (rt::real(2 * i + 1) / rt::real(n) - 1);
                const rt::real v = rt::real(0.9) * (rt::real(2 * j + 1) / rt::real(n) - 1);
                if (u * u + v * v > rt::real(0.81))
                    continue;
                const rt::vec3 target = ball.center + ball.radius * rt::vec3(u, v, std::sqrt(1 - u * u - v * v));
                const rt::color L = rt::ray_color(s, accel, rt::ray{eye, target - eye});
                ++rays;
                const rt::color want = km * sky;
                const bool exact = std::fabs(L.r - want.r) <= 1e-5f && std::fabs(L.g - want.g) <= 1e-5f &&
                                   std::fabs(L.b - want.b) <= 1e-5f;
                speckles += exact ? 0 : 1;
            }
        CAPTURE(scale);
        CAPTURE(rays);
        CHECK_MESSAGE(speckles == 0, "expected every pixel of the mirror ball to be km * background = "
                                         << doctest::toString(km * sky) << "; " << speckles << " of " << rays
                                         << " rays saw the ball itself again: start the reflected ray off the "
                                            "surface (rt::spawn_ray or rt::offset_ray_origin), not at the hit point");
        speckles_total += speckles;
    }
    CHECK_MESSAGE(speckles_total == 0, "expected no speckles at any scale, found " << speckles_total
                                                                                  << " over the three scales");
}
