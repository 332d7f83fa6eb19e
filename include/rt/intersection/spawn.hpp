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
// then refuses any t within its own error of 0 (watertight.hpp), so a ray spawned
// this way with tmin = 0 cannot hit the triangle it starts on.
//
// Grazing rays. The side the new ray leaves on is the sign of w . n, and that
// sign is only as good as w . n is: its rounding, and the normal's own
// direction error (a few ulps: triangle_normal, refine_sphere_hit), make it
// uncertain when w is within about gamma_8 |w|_1 of the surface's plane. From
// the origin on the wrong side such a ray crosses the surface, and a flat
// triangle that a ray leaving one of its points can never meet again is hit.
// (pbrt-v4's reintersection test, shapes_test.cpp, TEST(Triangle,
// Reintersect), finds them: 409 of 986,000 rays towards points re-hit their
// triangle in float, issue 19.) So:
//  - spawn_ray tilts a grazing direction off the surface, to the side its
//    origin is on, by twice that bound: a change of direction of about 1e-6
//    rad in float, and the ray then certainly leaves the surface;
//  - spawn_ray_to (a segment to a point: shadow rays) decides its side from
//    the target, and when the target lies within the uncertainty of the
//    surface's plane (it is as good as on the plane, seen from the hit), moves
//    the segment's far end off the plane to the origin's side as well, so the
//    whole segment lies on one side of the surface.
// A segment between two points strictly on one side of a plane does not meet
// it; the watertight test's sign decisions are exact (watertight.hpp), so no
// such ray or segment hits the triangle it leaves (tests/library_reintersect.cpp:
// 0 in float and double, against hundreds before).
#pragma once

#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../core/rounding.hpp"
#include "../core/vec.hpp"

namespace rt {

namespace detail {

/// PBR 3rd ed., sec. 3.9.5: the point p moved past its error box p +- p_error
/// along the unit normal n, to the side of the direction w.
inline vec3 offset_past_error_bounds(const vec3& p, const vec3& p_error, const vec3& n, const vec3& w)
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

} // namespace detail

/// Where a shadow segment towards a point stops: t < 1 - shadow_epsilon, so a
/// light that sits on a surface is not blocked by that surface (pbrt's
/// ShadowEpsilon, PBR 3rd ed., sec. 3.9.5).
constexpr real shadow_epsilon = real(1e-4);

namespace detail {

/// The uncertainty of w . n as the height gained along the true normal per
/// unit of t (see the top of this file): gamma_3 |w|_1 for the dot product,
/// about 3 u |w| for the normal's direction, 2 u |w|_1 for rounding the
/// direction the caller ends up with; |w|_1 >= |w|.
inline real grazing_bound(const vec3& w)
{
    return gamma_n(8) * (std::fabs(w.x) + std::fabs(w.y) + std::fabs(w.z));
}

/// p + lift, each coordinate rounded away from p (as offset_past_error_bounds does).
inline vec3 add_rounding_away(const vec3& p, const vec3& lift)
{
    vec3 moved = p + lift;
    for (int k = 0; k < 3; ++k) {
        if (lift[k] > 0)
            moved[k] = next_up(moved[k]);
        else if (lift[k] < 0)
            moved[k] = next_down(moved[k]);
    }
    return moved;
}

} // namespace detail

/// A ray leaving the hit `rec` in the direction `direction`, to be traced with
/// tmin = 0: its origin is offset past the rounding error of the hit point, to
/// the side of the geometric normal the direction points to. A direction that
/// grazes the surface (|w . n| within detail::grazing_bound) is tilted off it
/// to that side by twice the bound (see the top of this file); any other
/// direction is kept exactly.
inline ray spawn_ray(const hit_record& rec, const vec3& direction)
{
    const vec3& n = rec.geometric_normal;
    const real along = glm::dot(direction, n);
    const real side = along < 0 ? real(-1) : real(1);
    const real bound = detail::grazing_bound(direction);
    const vec3 d = std::fabs(along) <= bound ? direction + (side * 2 * bound) * n : direction;
    return ray{detail::offset_past_error_bounds(rec.point, rec.point_error, n, side * n), d};
}

/// The segment from the hit `rec` to the point `target`: a ray with t = 1 at
/// the target (trace it in [0, 1 - shadow_epsilon) for a shadow ray: pbrt's
/// SpawnRayTo, PBR 3rd ed., sec. 3.9.5). Its origin is offset past the hit
/// point's rounding error to the side of the surface the target is on; when
/// the target lies within the uncertainty of the surface's plane, its end is
/// moved off the plane to that side too (see the top of this file), by at
/// most a few times the hit point's rounding error plus about 1e-6 of the
/// segment's length in float.
inline ray spawn_ray_to(const hit_record& rec, const vec3& target)
{
    const vec3& n = rec.geometric_normal;
    const vec3 w = target - rec.point;
    const real along = glm::dot(w, n);
    const real side = along < 0 ? real(-1) : real(1);
    const vec3 origin = detail::offset_past_error_bounds(rec.point, rec.point_error, n, side * n);
    // how far the target's height above the true plane can be from `along`:
    // the hit point's error along n, and the uncertainty of w . n itself
    const real uncertainty = glm::dot(glm::abs(n), rec.point_error) + detail::grazing_bound(w);
    vec3 end = target;
    if (std::fabs(along) <= uncertainty)
        end = detail::add_rounding_away(target, (side * 2 * uncertainty) * n);
    return ray{origin, end - origin};
}

} // namespace rt
