// offset.hpp - a compared method, not the library's: where a secondary ray
// starts, so that it does not hit its own surface, by Wachter and Binder's
// offset (stage 06 compares it; read it after the stage).
//
// A hit point computed in floating point lies a little above or below the true
// surface. A shadow or reflection ray started exactly there may hit the surface
// it starts on ("shadow acne"). Three answers, compared on
// docs/stages/06-going-further.md with pbrt-v4's reintersection test
// (tests/library_reintersect.cpp prints and asserts the counts):
//
// * the fixed epsilon of the textbook (Fundamentals of Computer Graphics, 4th
//   ed., sec. 4.7; shadows_fixed_epsilon.hpp): one eps cannot fit every scale.
//
// * this header: Wachter and Binder, "A Fast and Robust Method for Avoiding
//   Self-Intersection", Ray Tracing Gems (2019), ch. 6: move p along the
//   geometric normal by a fixed number of units in the last place of each
//   coordinate (integer arithmetic on the float's bits), which scales with the
//   coordinate's own rounding error; near zero, where ulps vanish, add a tiny
//   fixed offset instead. Their constants for float: 256 ulps, and below
//   |p| = 1/32 an offset of 1/65536 n. It assumes p is as accurate as the
//   surface allows, and it fails where that does not hold: a coordinate much
//   smaller than the others (it moves each by its own ulps), long thin float
//   triangles, and in double small spheres near the origin, where the
//   near-zero offset scaled down for double is below the hit point's error.
//
// * what the library uses: spawn_ray and spawn_ray_to (spawn.hpp, PBR 3rd ed.,
//   sec. 3.9.5), which move past the hit point's own error bound
//   (hit_record::point_error) and pass the same test with no re-hit in float
//   and double.
#pragma once

#include <cmath>
#include <cstdint>

#include "../core/rounding.hpp"
#include "../core/vec.hpp"

namespace rt {

// detail::add_ulps, the move by units in the last place, is in rounding.hpp
// (next_up and next_down use it too).

/// The robust origin of a ray leaving the surface at p on the side of the unit
/// geometric normal n (Ray Tracing Gems ch. 6). To leave on the other side,
/// pass -n.
inline vec3 offset_ray_origin(const vec3& p, const vec3& n)
{
    // The constants of ch. 6 are for float; for double the same 256 ulps are
    // kept (rt's double path computes hit points in double too), and the
    // near-zero threshold and offset shrink by the 2^29 finer spacing.
    constexpr bool is_float = sizeof(real) == 4;
    constexpr real origin = real(1.0 / 32.0);
    constexpr real float_scale = is_float ? real(1.0 / 65536.0) : real(1.0 / 65536.0 / 536870912.0);
    constexpr real int_scale = real(256);
    vec3 result;
    for (int axis = 0; axis < 3; ++axis) {
        const auto ulps = std::int64_t(int_scale * n[axis]); // truncation, as in ch. 6
        result[axis] = std::fabs(p[axis]) < origin ? p[axis] + float_scale * n[axis]
                                                   : detail::add_ulps(p[axis], ulps);
    }
    return result;
}

} // namespace rt
