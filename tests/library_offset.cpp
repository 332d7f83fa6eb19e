// library_offset.cpp - the robust ray origin of Wachter and Binder (Ray Tracing
// Gems ch. 6, include/rt/offset.hpp) that stages 06 and 07 use: it lies on the
// normal's side of the surface and moves the point a few ulps only.
#include "rt_doctest.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <rt/accelerator.hpp>
#include <rt/light.hpp>
#include <rt/scene.hpp>
#include <rt/shadows.hpp>

namespace {

struct shadow_scene {
    rt::scene s;
    rt::vec3 o, n, t1, t2; // plane origin, normal and in-plane axes
    double scale;
    double shadow_radius;  // in units of `scale`
};

struct shadow_count {
    int lit_points = 0, shadow_points = 0;
    int acne = 0;  // points outside the shadow that the test calls shadowed
    int leaks = 0; // points inside the shadow that the test calls lit
};

/// Looks at the plane from above on a 73 x 73 grid of points (spacing 0.25) and
/// compares each plane hit's visibility of the light with the analytic disc,
/// leaving out a band of one grid step around the shadow's edge.
template <class Visible>
shadow_count count_errors(const shadow_scene& q, Visible&& visible)
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


} // namespace

TEST_CASE("the robust origin lies on the normal's side of the surface, and moves a few ulps only")
{
    const rt::vec3 n = glm::normalize(rt::vec3(0.3f, 1.0f, 0.2f));
    for (double magnitude : {1e-6, 1e-2, 1.0, 1e3, 1e6}) {
        const rt::vec3 p = rt::real(magnitude) * rt::vec3(0.6f, -0.48f, 0.64f);
        const rt::vec3 moved = rt::offset_ray_origin(p, n);
        CAPTURE(magnitude);
        CHECK(glm::dot(moved - p, n) > 0);
        // at most 256 ulps of the coordinate in each axis (or 2^-16 near zero)
        for (int axis = 0; axis < 3; ++axis) {
            const rt::real x = std::fabs(p[axis]);
            const double ulp = double(std::nextafter(x, std::numeric_limits<rt::real>::infinity()) - x);
            const double near_zero = sizeof(rt::real) == 4 ? 1.0 / 65536 : 1.0 / 65536 / 536870912.0;
            const double bound = x < rt::real(1.0 / 32) ? near_zero : 256 * ulp;
            CHECK(std::fabs(double(moved[axis] - p[axis])) <= bound * 1.0001);
        }
    }
}
