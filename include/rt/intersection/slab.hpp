// slab.hpp - does a ray meet an axis-aligned box? The slab test, twice.
//
// A box is the intersection of three slabs, lo[k] <= x_k <= hi[k]. The ray
// p + t d is inside slab k for t between (lo[k] - p_k) / d_k and
// (hi[k] - p_k) / d_k; it meets the box where the three intervals overlap
// (Fundamentals of Computer Graphics, 4th ed., sec. 12.3.1, "Bounding Boxes":
// a = 1/d_k, the near plane chosen by the sign of a, the intervals
// intersected).
//
// hit_box_textbook is the stage-04 exercise: the method as the book gives it.
// hit_box_robust is the library's, and what the student's groups (groups.hpp)
// traverse with. It differs from the book in two places, both from Ize,
// "Robust BVH Ray Traversal", JCGT 2(2), 2013, and Williams, Barrus, Morley,
// Shirley, "An Efficient and Robust Ray-Box Intersection Algorithm", JGT
// 10(1), 2005:
//  - A ray lying in a slab plane (p_k = lo[k], d_k = 0) gives
//    (lo[k] - p_k) * (1/d_k) = 0 * inf = NaN. Each running bound is updated
//    as `t_near > t0 ? t_near : t0`, a comparison that is false for a NaN, so
//    the NaN leaves the bound as it was: the ray counts as inside that slab
//    (the box is closed) and no NaN reaches the result.
//  - The two bounds of a ray through an edge or a corner are equal in exact
//    arithmetic, and each is rounded (the rounded 1/d, the difference, the
//    product): t0 can come out a little larger than t1. Ize bounds each
//    computed t within gamma_3 of the exact one, so t0 <= t1 (1 + 2 gamma_3)
//    never culls a box the ray meets. The factor multiplies min(t_far, tmax),
//    so a box touched at exactly tmax (the closest hit so far) is kept too.
// A -0 in a direction needs nothing: 1/-0 = -inf, whose sign picks hi as the
// near plane, as for any negative component; the book does the same.
//
// rt::hit_box (bvh/box_test.hpp) is the same robust test on a prepared ray, for the
// fast path; this header is the readable one.
#pragma once

#include <algorithm>
#include <cmath>

#include "../core/aabb.hpp"
#include "../core/ray.hpp"
#include "../core/rounding.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The textbook slab test (FCG 4th ed., sec. 12.3.1): true when the ray meets
/// `box` for some t in [tmin, tmax]; then tnear is where it enters, the
/// largest of tmin and the three near planes' t. On a miss tnear is left
/// as it was. For each axis k, with a = 1/d_k:
///     a >= 0:  t_near = a (lo[k] - p_k),  t_far = a (hi[k] - p_k)
///     a < 0:   t_near = a (hi[k] - p_k),  t_far = a (lo[k] - p_k)
/// and the ray meets the box when max(tmin, t_near over k) <= min(tmax, t_far over k).
inline bool hit_box_textbook(const aabb& box, const ray& r, real tmin, real tmax, real& tnear)
{
    // RT_EXERCISE_BEGIN(stage04: ray-box slab test)
    // Hint: a = 1 / d_k is +-inf for a zero component, with the sign of the zero:
    //   test the sign of a, not of d_k, and a -0 takes care of itself.
    real t_near[3], t_far[3];
    for (int k = 0; k < 3; ++k) {
        const real a = real(1) / r.direction[k];
        if (a >= 0) {
            t_near[k] = a * (box.lo[k] - r.origin[k]);
            t_far[k] = a * (box.hi[k] - r.origin[k]);
        } else {
            t_near[k] = a * (box.hi[k] - r.origin[k]);
            t_far[k] = a * (box.lo[k] - r.origin[k]);
        }
    }
    // the three intervals and [tmin, tmax] intersected
    const real t_enter = std::max(std::max(std::max(t_near[0], t_near[1]), t_near[2]), tmin);
    const real t_exit = std::min(std::min(std::min(t_far[0], t_far[1]), t_far[2]), tmax);
    if (!(t_enter <= t_exit))
        return false;
    tnear = t_enter;
    return true;
    // RT_EXERCISE_END
}

/// Ize 2013: the computed far bound is scaled by 1 + 2 gamma_3 before it is
/// compared with the near one, so that rounding never culls a box the ray meets.
constexpr real slab_robust_far_factor = 1 + 2 * gamma_n(3);

/// The robust slab test (see the top of this file): true when the ray meets
/// the closed box for some t in [tmin, tmax], up to the rounding Ize's factor
/// allows; tnear is then where it enters (never a NaN). On a miss tnear is
/// left as it was. tmin is taken to be >= 0 (the factor widens t_far away
/// from 0). An empty box (lo > hi on an axis) is met by no ray.
inline bool hit_box_robust(const aabb& box, const ray& r, real tmin, real tmax, real& tnear)
{
    real t0 = tmin, t1 = tmax;
    for (int k = 0; k < 3; ++k) {
        const real inverse = real(1) / r.direction[k]; // IEEE: 1/+0 = +inf, 1/-0 = -inf
        const bool negative = std::signbit(inverse);
        const real near_plane = negative ? box.hi[k] : box.lo[k];
        const real far_plane = negative ? box.lo[k] : box.hi[k];
        const real t_near = (near_plane - r.origin[k]) * inverse;
        const real t_far = (far_plane - r.origin[k]) * inverse;
        t0 = t_near > t0 ? t_near : t0; // false for a NaN: t0 stays
        t1 = t_far < t1 ? t_far : t1;   // false for a NaN: t1 stays
    }
    if (box.empty() || !(t0 <= t1 * slab_robust_far_factor))
        return false;
    tnear = t0;
    return true;
}

} // namespace rt
