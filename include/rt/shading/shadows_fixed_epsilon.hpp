// shadows_fixed_epsilon.hpp - the textbook's shadow ray, for comparison (stage 06).
//
// Read this after you finish stage 06: it is the answer the course's first
// try gives, and the stage-06 tests and program (--offset fixed) show where it
// fails. The textbook (Fundamentals of Computer Graphics, 4th ed., sec. 4.7)
// starts the shadow ray exactly at the computed hit point and ignores hits
// closer than a fixed epsilon. The rounding error of a hit point grows with
// its coordinates (one float ulp at 1e4 is 0.001), so far from the origin
// eps = 1e-4 is smaller than that error and the surface shadows itself
// ("shadow acne"); rt::light_visible (shadows.hpp) spawns the ray past the
// hit point's own error bound instead (spawn.hpp).
#pragma once

#include "../core/hit_record.hpp"
#include "../scene/light_sample.hpp"
#include "../core/ray.hpp"
#include "../core/vec.hpp"

namespace rt {

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
