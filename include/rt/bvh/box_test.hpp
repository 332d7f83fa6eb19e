// bvh/box_test.hpp - the robust slab test of a ray against a box.
//
// Williams, Barrus, Morley, Shirley, "An Efficient and Robust Ray-Box
// Intersection Algorithm", JGT 10(1), 2005; Ize, "Robust BVH Ray Traversal",
// JCGT 2(2), 2013:
//  - 1/d as IEEE gives it: +-inf for a zero component, with the sign of the
//    zero, so axis-parallel rays need no special case; the near plane of each
//    axis is chosen by the sign of 1/d.
//  - A ray lying in a slab plane gives 0 * inf = NaN; each comparison is
//    written so that a NaN leaves the running interval as it was (the box is
//    closed), and no NaN reaches a result.
//  - Rounding can make the computed t_far smaller than t_near when the exact
//    values are equal (a ray through an edge or corner); Ize shows the computed
//    values are within gamma_3 of the exact ones, so t_near <= t_far (1 + 2
//    gamma_3) never culls a box the ray meets. The factor is applied to
//    min(t_far, t_max), so a hit at exactly the closest t is not culled either.
//
//     real tnear;
//     if (rt::hit_box(box, rt::make_box_ray(ray), 0, t_max, tnear)) { /* enter at tnear */ }
#pragma once

#include <cmath>

#include "../core/aabb.hpp"
#include "../core/ray.hpp"
#include "../core/rounding.hpp"
#include "../intersection/slab.hpp" // slab_robust_far_factor, Ize's 1 + 2 gamma_3
#include "../core/vec.hpp"

namespace rt {

/// A ray prepared for box tests: its origin, 1/d (+-inf for a +-0
/// component) and, per axis, 1 when 1/d is negative (the near plane is hi).
struct box_ray {
    vec3 origin{0};
    vec3 inv_dir{0};
    int negative[3] = {0, 0, 0};
};

inline box_ray make_box_ray(const ray& r)
{
    box_ray b;
    b.origin = r.origin;
    for (int k = 0; k < 3; ++k) {
        b.inv_dir[k] = real(1) / r.direction[k]; // IEEE: 1/+0 = +inf, 1/-0 = -inf
        b.negative[k] = std::signbit(b.inv_dir[k]) ? 1 : 0;
    }
    return b;
}

/// The robust slab test (see the top of this file): true when the ray meets
/// `box` within [tmin, tmax]; `tnear` is then where it enters. `far_factor`
/// is Ize's 1 + 2 gamma_3; the tests pass 1 to show what goes wrong without it.
inline bool hit_box(const aabb& box, const box_ray& r, real tmin, real tmax, real& tnear,
                    real far_factor = slab_robust_far_factor)
{
    real t0 = tmin, t1 = tmax;
    for (int k = 0; k < 3; ++k) {
        const real near_plane = r.negative[k] ? box.hi[k] : box.lo[k];
        const real far_plane = r.negative[k] ? box.lo[k] : box.hi[k];
        const real t_near = (near_plane - r.origin[k]) * r.inv_dir[k];
        const real t_far = (far_plane - r.origin[k]) * r.inv_dir[k];
        t0 = t_near > t0 ? t_near : t0; // a NaN (ray in this plane) keeps t0
        t1 = t_far < t1 ? t_far : t1;   // a NaN keeps t1
    }
    tnear = t0;
    return t0 <= t1 * far_factor;
}

} // namespace rt
