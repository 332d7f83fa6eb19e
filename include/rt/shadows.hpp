// shadows.hpp - is a light visible from a surface point? (stage 06)
//
// Fundamentals of Computer Graphics, 4th ed., sec. 4.7: a point is in shadow
// when a ray from it towards the light hits something before the light. Any hit
// will do (no need for the closest), and only hits closer than the light count.
//
// Where the shadow ray starts matters (offset.hpp): started exactly at the
// computed hit point, it can hit its own surface ("shadow acne"). The library
// starts it at offset_ray_origin(p, n_g), the robust offset of Ray Tracing Gems
// ch. 6; light_visible_fixed_epsilon keeps the textbook's fixed epsilon for
// comparison (tests and benchmarks show where it fails).
#pragma once

#include "hit_record.hpp"
#include "light.hpp"
#include "offset.hpp"
#include "ray.hpp"
#include "vec.hpp"

namespace rt {

/// True when nothing in `accel` blocks the segment from the hit to the light.
/// `accel` is anything with any_hit(ray, tmin, tmax) (rt::accelerator).
template <class Accelerator>
bool light_visible(const Accelerator& accel, const hit_record& hit, const light_sample& sample)
{
    // RT_EXERCISE_BEGIN(stage06: shadow ray)
    // Leave on the side the light is on; the light was already found to be on
    // the outer side of the geometric normal (shading.hpp), so that is +n_g.
    const vec3 origin = offset_ray_origin(hit.point, hit.geometric_normal);
    const ray shadow{origin, sample.l};
    // sample.l is a unit vector, so t is a distance; stop just short of a point
    // light (the light itself is not an occluder), or never for a directional one.
    const real tmax = sample.distance * (real(1) - real(1e-4)); // inf stays inf
    return !accel.any_hit(shadow, real(0), tmax);
    // RT_EXERCISE_END
}

/// The textbook's version, kept for comparison: the shadow ray starts exactly
/// at the hit point and ignores hits closer than a fixed epsilon.
template <class Accelerator>
bool light_visible_fixed_epsilon(const Accelerator& accel, const hit_record& hit, const light_sample& sample,
                                 real epsilon = real(1e-4))
{
    const ray shadow{hit.point, sample.l};
    return !accel.any_hit(shadow, epsilon, sample.distance * (real(1) - real(1e-4)));
}

} // namespace rt
