// shadows.hpp - is a light visible from a surface point? (stage 06)
//
// Fundamentals of Computer Graphics, 4th ed., sec. 4.7: a point is in shadow
// when a ray from it towards the light hits something before the light. Any hit
// will do (no need for the closest), and only hits closer than the light count.
//
// Where the shadow ray starts matters: started exactly at the computed hit
// point, it can hit its own surface ("shadow acne"). The library spawns it
// past the hit point's rounding error (spawn.hpp, PBR 3rd ed., sec. 3.9.5):
// spawn_ray_to for the segment to a point light, spawn_ray for a directional
// light; no such ray hits the surface it leaves, at any scale
// (tests/library_reintersect.cpp). offset.hpp keeps the Ray Tracing Gems
// offset that stage 06 teaches, and shadows_fixed_epsilon.hpp (read it after
// you finish this stage) the textbook's fixed epsilon, for comparison; the
// tests and benchmarks show where they fail.
#pragma once

#include <cmath>
#include <limits>

#include "../core/hit_record.hpp"
#include "../scene/light_sample.hpp"
#include "../intersection/offset.hpp" // the Ray Tracing Gems offset, which stage 06 compares with
#include "../core/ray.hpp"
#include "../intersection/spawn.hpp"
#include "../core/vec.hpp"

namespace rt {

/// True when nothing in `accel` blocks the segment from the hit to the light.
/// `accel` is anything with any_hit(ray, tmin, tmax) (rt::accelerator).
template <class Accelerator>
bool light_visible(const Accelerator& accel, const hit_record& hit, const light_sample& sample)
{
    // RT_EXERCISE_BEGIN(stage06: shadow ray)
    // A directional light is infinitely far: a ray towards it, never ending.
    if (!std::isfinite(sample.distance))
        return !accel.any_hit(spawn_ray(hit, sample.l), real(0), std::numeric_limits<real>::infinity());
    // A point light: the segment from the hit to the light (t = 1 at the
    // light), stopped just short of it (the light itself is not an occluder).
    const ray shadow = spawn_ray_to(hit, hit.point + sample.distance * sample.l);
    return !accel.any_hit(shadow, real(0), real(1) - shadow_epsilon);
    // RT_EXERCISE_END
}

} // namespace rt

// The textbook's fixed-epsilon shadow ray, which the stage-06 tests and program
// compare with: at the end, so that it is not read as part of the exercise.
#include "shadows_fixed_epsilon.hpp"
