// spawn.hpp - start a new ray at a hit point without hitting the same surface again (stage 04 on).
//
// A computed hit point is rounded: it lies a little in front of or behind the
// surface, and a shadow or reflection ray started there can hit the surface it
// starts on ("acne"). A fixed epsilon offset is wrong at some scale: too small
// far from the origin (where the rounding is larger than the epsilon), too
// large for small geometry. The honest offset is the rounding error itself
// (Physically Based Rendering, 3rd ed., sec. 3.9.5): the exact surface point
// lies in the box point +- point_error (hit_record, filled by the scene-level
// intersection), so moving the origin along the geometric normal n by
//     d = |n_x| e_x + |n_y| e_y + |n_z| e_z   (the box's extent along n)
// to the side the new ray leaves on, and rounding each coordinate one more
// step away, puts the origin past the surface. The watertight triangle test
// then refuses any t within its own error of 0 (triangle.hpp), so a ray spawned
// this way with tmin = 0 cannot hit the triangle it starts on.
#pragma once

#include <glm/common.hpp>

#include "hit_record.hpp"
#include "ray.hpp"
#include "rounding.hpp"
#include "vec.hpp"

namespace rt {

/// PBR 3rd ed., sec. 3.9.5: the point p moved past its error box p +- p_error
/// along the unit normal n, to the side of the direction w.
inline vec3 offset_ray_origin(const vec3& p, const vec3& p_error, const vec3& n, const vec3& w)
{
    const real d = glm::dot(glm::abs(n), p_error);
    vec3 offset = d * n;
    if (glm::dot(w, n) < 0)
        offset = -offset;
    vec3 moved = p + offset;
    for (int k = 0; k < 3; ++k) { // round away from p, so the rounding of the sum cannot pull it back
        if (offset[k] > 0)
            moved[k] = next_up(moved[k]);
        else if (offset[k] < 0)
            moved[k] = next_down(moved[k]);
    }
    return moved;
}

/// A ray leaving the hit `rec` in the direction `direction`, to be traced with
/// tmin = 0: its origin is offset past the rounding error of the hit point.
inline ray spawn_ray(const hit_record& rec, const vec3& direction)
{
    return ray{offset_ray_origin(rec.point, rec.point_error, rec.geometric_normal, direction), direction};
}

} // namespace rt
