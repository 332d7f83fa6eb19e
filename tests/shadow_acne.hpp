// shadow_acne.hpp - the shadow-acne measurement that tests/stage06_shadows.cpp
// asserts and prints, and tests/docs_figures.cpp quotes in
// docs/stages/06-shadows.md: one copy of the code, so the page, the printed
// table and the assertions cannot disagree. No doctest here (docs_figures is
// a plain program).
//
// The scene: a sphere above a plane, with a point light on the plane's normal
// through the sphere's centre. The shadow is then a disc whose radius follows
// from similar triangles (Fundamentals of Computer Graphics, 4th ed., sec. 4.7
// for the shadow ray): light height H, centre height C, radius R give the
// tangent cone's half angle a with sin a = R / (H - C), and the shadow radius
// on the plane is H tan a. The intersection is the library's (unmarked)
// accelerator; the robust visibility is the stage-06 exercise light_visible,
// the fixed epsilon the library's light_visible_fixed_epsilon.
#pragma once

#include <cmath>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/core/hit_record.hpp>
#include <rt/scene/light.hpp>
#include <rt/scene/light_sample.hpp>
#include <rt/scene/scene.hpp>
#include <rt/shading/shadows.hpp>
#include <rt/shading/shadows_fixed_epsilon.hpp>
#include <rt/core/vec.hpp>

namespace rt_test {

struct shadow_scene {
    rt::scene s;
    rt::vec3 o, n, t1, t2; // plane origin, normal and in-plane axes
    double scale = 1;
    double shadow_radius = 0; // in units of `scale`
};

/// A tilted square plane of half size 10, a unit sphere at height 2 and a point
/// light at height 8, all scaled by `scale` and moved to `origin`.
inline shadow_scene make_shadow_scene(double scale, rt::vec3 origin)
{
    shadow_scene q;
    q.scale = scale;
    q.o = origin;
    q.n = glm::normalize(rt::vec3(0.3f, 1.0f, 0.2f));
    q.t1 = glm::normalize(glm::cross(q.n, rt::vec3(0, 0, 1)));
    q.t2 = glm::cross(q.t1, q.n);
    const rt::real s = rt::real(scale);
    auto at = [&](double x, double z) { return q.o + s * (rt::real(x) * q.t1 + rt::real(z) * q.t2); };
    rt::triangle a, b;
    a.a = at(-10, -10);
    a.b = at(10, -10);
    a.c = at(10, 10);
    b.a = at(-10, -10);
    b.b = at(10, 10);
    b.c = at(-10, 10);
    q.s.shapes.emplace_back(a);
    q.s.shapes.emplace_back(b);
    rt::sphere ball;
    ball.center = q.o + s * rt::real(2) * q.n;
    ball.radius = s;
    q.s.shapes.emplace_back(ball);
    rt::light bulb;
    bulb.kind = rt::light_kind::point;
    bulb.position = q.o + s * rt::real(8) * q.n;
    q.s.lights.push_back(bulb);
    const double H = 8, C = 2, R = 1, sin_a = R / (H - C);
    q.shadow_radius = H * sin_a / std::sqrt(1 - sin_a * sin_a);
    return q;
}

struct shadow_count {
    int lit_points = 0, shadow_points = 0;
    int acne = 0;  // points outside the shadow that the test calls shadowed
    int leaks = 0; // points inside the shadow that the test calls lit
};

/// Looks at the plane from above on a 73 x 73 grid of points (spacing 0.25) and
/// compares each plane hit's visibility of the light with the analytic disc,
/// leaving out a band of one grid step around the shadow's edge.
template <class Visible>
shadow_count count_shadow_errors(const shadow_scene& q, Visible&& visible)
{
    const rt::accelerator accel(q.s);
    const rt::real s = rt::real(q.scale);
    const rt::vec3 eye = q.o + s * (rt::real(6) * q.t1 + rt::real(12) * q.n);
    const double step = 0.25;
    shadow_count count;
    for (int i = -36; i <= 36; ++i)
        for (int k = -36; k <= 36; ++k) {
            const rt::vec3 target = q.o + s * (rt::real(i * step) * q.t1 + rt::real(k * step) * q.t2);
            const rt::ray r{eye, target - eye};
            rt::hit_record hit;
            if (!accel.closest_hit(r, 0, rt::real(1e30), hit) || hit.shape > 1)
                continue; // the ball is in the way
            const rt::vec3 local = (hit.point - q.o) / s;
            const rt::vec3 radial = local - glm::dot(local, q.n) * q.n;
            const double rho = double(glm::length(radial));
            const rt::light_sample sample = rt::sample_light(q.s.lights[0], hit.point);
            const bool lit = visible(accel, hit, sample);
            if (rho > q.shadow_radius + step) {
                ++count.lit_points;
                count.acne += lit ? 0 : 1;
            } else if (rho < q.shadow_radius - step) {
                ++count.shadow_points;
                count.leaks += lit ? 1 : 0;
            }
        }
    return count;
}

/// The stage-06 exercise: the error-bounded spawn.
inline bool robust_visible(const rt::accelerator& accel, const rt::hit_record& hit, const rt::light_sample& sample)
{
    return rt::light_visible(accel, hit, sample);
}

/// The textbook's fixed epsilon, 1e-4.
inline bool fixed_epsilon_visible(const rt::accelerator& accel, const rt::hit_record& hit, const rt::light_sample& sample)
{
    return rt::light_visible_fixed_epsilon(accel, hit, sample, rt::real(1e-4));
}

/// One row of the acne table: the scene scaled about the origin, or at scale 1
/// moved away from it.
struct acne_setting {
    int scale_exponent = 0;  // the scene scaled by 10^scale_exponent
    int offset_exponent = 0; // moved 10^offset_exponent away (used when moved)
    bool moved = false;
    double scale() const { return moved ? 1.0 : std::pow(10.0, scale_exponent); }
    double offset() const { return moved ? std::pow(10.0, offset_exponent) : 0.0; }
    shadow_scene scene() const { return make_shadow_scene(scale(), rt::real(offset()) * rt::vec3(0.6f, -0.48f, 0.64f)); }
};

/// Scales 10^-3 ... 10^5, then offsets 10^-3 ... 10^5 (float) or 10^12
/// (double: its hit points are 2^29 times finer, so a fixed epsilon fails
/// only further out).
inline std::vector<acne_setting> acne_settings()
{
    std::vector<acne_setting> settings;
    for (int e = -3; e <= 5; ++e)
        settings.push_back({e, 0, false});
    const int largest_offset = sizeof(rt::real) == 4 ? 5 : 12;
    for (int e = -3; e <= largest_offset; ++e)
        settings.push_back({0, e, true});
    return settings;
}

} // namespace rt_test
