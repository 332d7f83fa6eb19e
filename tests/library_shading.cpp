// library_shading.cpp - the library's shading around the stage-05 exercise:
// shapes without a material are shaded with the default material. No exercise
// is called.
#include "rt_doctest.hpp"

#include <cmath>

#include <rt/hit_record.hpp>
#include <rt/scene.hpp>
#include <rt/shading.hpp>
#include <rt/sphere_stable.hpp>

namespace {

const auto always_visible = [](const rt::light_sample&) { return true; };

rt::material test_material()
{
    rt::material m;
    m.ka = {0.2f, 0.1f, 0.05f};
    m.kd = {0.7f, 0.5f, 0.3f};
    m.ks = {0.4f, 0.4f, 0.4f};
    m.p = 20;
    return m;
}

/// A scene of one unit sphere at the origin with the test material and one
/// directional light shining along -z (so l = +z everywhere).
rt::scene one_sphere_scene()
{
    rt::scene s;
    s.materials.push_back(test_material());
    rt::sphere ball;
    ball.material = 0;
    s.shapes.emplace_back(ball);
    rt::light sun;
    sun.kind = rt::light_kind::directional;
    sun.direction = {0, 0, -1};
    sun.intensity = {1.0f, 0.9f, 0.8f};
    s.lights.push_back(sun);
    s.ambient = {0.3f, 0.3f, 0.3f};
    return s;
}

/// The colour of the orthographic ray through (x, y), looking along -z.
rt::color shade_at(const rt::scene& s, double x, double y)
{
    const rt::ray r{rt::vec3(rt::real(x), rt::real(y), 10), rt::vec3(0, 0, -1)};
    rt::hit_record hit;
    REQUIRE(rt::hit_sphere(std::get<rt::sphere>(s.shapes[0]), r, 0, 100, hit));
    return rt::direct_lighting(s, hit, r.direction, always_visible);
}

void check_color(const rt::color& got, double r, double g, double b, double eps = 1e-5)
{
    CHECK(got.r == doctest::Approx(r).epsilon(eps));
    CHECK(got.g == doctest::Approx(g).epsilon(eps));
    CHECK(got.b == doctest::Approx(b).epsilon(eps));
}

} // namespace

TEST_CASE("the default material shades shapes without a material")
{
    rt::scene s = one_sphere_scene();
    std::get<rt::sphere>(s.shapes[0]).material = -1;
    s.lights.clear();
    const rt::color L = shade_at(s, 0, 0);
    const rt::color expected = s.default_material.ka * s.ambient;
    check_color(L, expected.r, expected.g, expected.b);
}
