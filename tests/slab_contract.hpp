// slab_contract.hpp - the cases every robust ray-box (slab) test passes,
// written once for the two the library has: rt::hit_box_robust (slab.hpp,
// beside the stage-04 exercise) and the BVH's rt::hit_box (bvh/box_test.hpp). Axis-
// parallel rays, rays lying in a slab plane (0 * inf), -0 in a direction,
// flat and empty boxes, the ends of [tmin, tmax]: a hit never reports a NaN.
#pragma once

#include "rt_doctest.hpp"

#include <cmath>
#include <limits>

#include <rt/core/aabb.hpp>
#include <rt/core/ray.hpp>

namespace rt_test {

/// `hit_box_under_test(box, ray, tmin, tmax, tnear)`: true when the ray meets the closed box
/// in [tmin, tmax], with tnear where it enters (tmin for an origin inside).
template <class Hit>
void check_robust_slab(Hit&& hit_box_under_test)
{
    using rt::real;
    using rt::vec3;
    constexpr real inf = std::numeric_limits<real>::infinity();
    rt::aabb box;
    box.lo = vec3(-1, -1, -1);
    box.hi = vec3(1, 2, 3);
    const real zero = 0, minus_zero = -real(0);
    real tnear = -1;
    auto hits = [&](const vec3& o, const vec3& d, real tmin = 0, real tmax = std::numeric_limits<real>::infinity()) {
        tnear = std::numeric_limits<real>::quiet_NaN();
        const bool met = hit_box_under_test(box, rt::ray{o, d}, tmin, tmax, tnear);
        if (met)
            CHECK_FALSE(std::isnan(tnear));
        return met;
    };
    CHECK(hits({-5, 0, 0}, {1, zero, zero}));
    CHECK(tnear == 4);
    CHECK_FALSE(hits({-5, 2.5f, 0}, {1, zero, zero}));
    CHECK_FALSE(hits({-5, 0, 0}, {-1, zero, zero})); // pointing away
    // in a slab plane (origin on the plane, direction inside it): the box is closed
    CHECK(hits({-5, 2, 0}, {1, zero, zero}));
    CHECK(tnear == 4);
    CHECK(hits({-5, -1, 0}, {1, zero, zero}));
    CHECK(hits({-5, 2, 0}, {1, minus_zero, zero}));
    CHECK(hits({-5, -1, 0}, {1, minus_zero, minus_zero}));
    CHECK(hits({-1, 0, -7}, {zero, zero, 2})); // in the plane x = lo
    CHECK(tnear == 3);
    CHECK(hits({1, 0, -7}, {minus_zero, zero, 2})); // in the plane x = hi, -0
    CHECK(hits({-5, 2, 3}, {1, minus_zero, zero})); // along an edge
    CHECK(hits({1, 2, 3}, {minus_zero, minus_zero, -1})); // down an edge from a corner
    CHECK(tnear == 0);
    // just outside a plane, parallel to it: a miss
    CHECK_FALSE(hits({-5, std::nextafter(real(2), real(3)), 0}, {1, zero, zero}));
    CHECK_FALSE(hits({-5, std::nextafter(real(-1), real(-2)), 0}, {1, minus_zero, zero}));
    // a flat box (lo = hi on y), met only in its plane or across it
    box.lo.y = box.hi.y = real(0.5);
    CHECK(hits({-5, 0.5f, 0}, {1, zero, zero}));
    CHECK(hits({0, 5, 0}, {zero, -1, zero}));
    CHECK(tnear == real(4.5));
    CHECK_FALSE(hits({-5, 0.6f, 0}, {1, zero, zero}));
    // the interval: an origin inside enters at tmin; tmax before the box, tmin after it
    box.lo = vec3(-1);
    box.hi = vec3(1);
    CHECK(hits({0, 0, 0}, {1, 1, 1}, real(0.25)));
    CHECK(tnear == real(0.25));
    CHECK_FALSE(hits({-5, 0, 0}, {1, 0, 0}, 0, 3));
    CHECK_FALSE(hits({-5, 0, 0}, {1, 0, 0}, 7));
    CHECK(hits({-5, 0, 0}, {1, 0, 0}, 0, 4)); // touched at exactly tmax: kept
    // the empty box (lo = +inf, hi = -inf) is met by nothing
    box = rt::aabb{};
    CHECK_FALSE(hit_box_under_test(box, rt::ray{vec3(0), vec3(1, 0, 0)}, real(0), inf, tnear));
    CHECK_FALSE(hit_box_under_test(box, rt::ray{vec3(0), vec3(zero, minus_zero, 1)}, real(0), inf, tnear));
}

} // namespace rt_test
