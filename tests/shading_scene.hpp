// shading_scene.hpp - the scene the shading suites share (stage 05's and the
// library's): one unit sphere at the origin, one material, one directional
// light along -z, seen by orthographic rays along -z. Every expected value in
// those suites is worked out by hand from this geometry.
#pragma once

#include <variant>

#include <rt/core/hit_record.hpp>
#include <rt/scene/scene.hpp>
#include <rt/shading/shading.hpp>
#include <rt/intersection/sphere_stable.hpp>

#include "rt_doctest.hpp"

namespace rt_test {

inline const auto always_visible = [](const rt::light_sample&) { return true; };

/// ka (0.2, 0.1, 0.05), kd (0.7, 0.5, 0.3), ks 0.4, p 20.
inline rt::material test_material()
{
    rt::material m;
    m.ka = {0.2f, 0.1f, 0.05f};
    m.kd = {0.7f, 0.5f, 0.3f};
    m.ks = {0.4f, 0.4f, 0.4f};
    m.p = 20;
    return m;
}

/// A scene of one unit sphere at the origin with the test material and one
/// directional light shining along -z (so l = +z everywhere), ambient 0.3.
inline rt::scene one_sphere_scene()
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

/// The color of the orthographic ray through (x, y), looking along -z.
inline rt::color shade_at(const rt::scene& s, double x, double y)
{
    const rt::ray r{rt::vec3(rt::real(x), rt::real(y), 10), rt::vec3(0, 0, -1)};
    rt::hit_record hit;
    REQUIRE_MESSAGE(rt::hit_sphere(std::get<rt::sphere>(s.shapes[0]), r, 0, 100, hit),
                    "expected the test's ray to hit the sphere (the library's hit_sphere: a fault of the test "
                    "scene, not of your shading)");
    return rt::direct_lighting(s, hit, r.direction, always_visible);
}

} // namespace rt_test
