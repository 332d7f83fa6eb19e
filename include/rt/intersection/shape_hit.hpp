// shape_hit.hpp - the closest hit of a ray with one shape of a scene, by the
// library's robust methods (rt::hit_sphere of sphere_stable.hpp, the
// watertight test of watertight.hpp for triangles and meshes).
//
// hit_shape is what the list (hit_list.hpp) tests each shape with by default;
// refine_sphere_hit is shared with the scene-level accelerator
// (accelerator.hpp), so the list and the accelerator fill a sphere's hit
// record with the same code. No exercise is included here.
#pragma once

#include <cmath>
#include <limits>
#include <variant>

#include <glm/common.hpp>

#include "../core/hit_record.hpp"
#include "../scene/mesh.hpp"
#include "mesh_hit.hpp"
#include "../core/ray.hpp"
#include "../core/rounding.hpp"
#include "../scene/scene.hpp"
#include "sphere_stable.hpp"
#include "../core/vec.hpp"
#include "watertight.hpp"

namespace rt {

namespace detail {

/// The hit point and normal of a sphere hit that hit_sphere found on ray r,
/// computed again relative to the centre. The point p + t d itself is no
/// good for the normal when the ray comes from far away: its rounding error,
/// about u |p - c| (u the unit roundoff), can exceed R, and normalize(p - c)
/// then points anywhere (issue 19: rays from 10^8 at spheres of radius 10^-3).
/// In the wider type of sphere_stable.hpp, with f = p - c and d^ = d / |d| (Ray
/// Tracing Gems ch. 7, the stable method's perpendicular vector):
///     l = f - (f.d^) d^          the centre's perpendicular to the line,
///     s = sqrt(R^2 - |l|^2)      half the chord,
///     x = l -+ s d^              the hit relative to c (- for the nearer root),
/// so |x| = R exactly in exact arithmetic, and x's error is a few rounding
/// units of the wider type times |f|, 2^-29 times less than in float. The
/// point is c + x rounded once; its error bound is that rounding (gamma_1
/// |point|, PBR 3rd ed., sec. 3.9.4) plus 16 units of the wider type times
/// |f| + R + |c| for x's own computation. The normal is x / |x|, turned to
/// face the ray. t is left as hit_sphere computed it.
inline void refine_sphere_hit(const sphere& s, const ray& r, hit_record& rec)
{
    using wide = detail::wider_real;
    const wide f[3] = {wide(r.origin.x) - wide(s.center.x), wide(r.origin.y) - wide(s.center.y),
                       wide(r.origin.z) - wide(s.center.z)};
    const wide dw[3] = {wide(r.direction.x), wide(r.direction.y), wide(r.direction.z)};
    const wide d_length = std::sqrt(dw[0] * dw[0] + dw[1] * dw[1] + dw[2] * dw[2]);
    if (!(d_length > 0) || !std::isfinite(d_length))
        return;
    const wide d[3] = {dw[0] / d_length, dw[1] / d_length, dw[2] / d_length};
    const wide f_along = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
    const wide l[3] = {f[0] - f_along * d[0], f[1] - f_along * d[1], f[2] - f_along * d[2]};
    const wide R = wide(s.radius);
    const wide chord2 = R * R - (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    const wide half_chord = chord2 > 0 ? std::sqrt(chord2) : wide(0);
    // which root hit_sphere took: the same call gives the same bits (the two
    // roots can be closer than t's rounding, so t alone cannot tell them apart)
    real t0 = 0, t1 = 0;
    const bool nearer = !sphere_roots_stable(s, r, t0, t1) || rec.t == t0;
    const wide along = nearer ? -half_chord : half_chord;
    const wide x[3] = {l[0] + along * d[0], l[1] + along * d[1], l[2] + along * d[2]};
    const wide x_length = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    if (!(x_length > 0) || !std::isfinite(x_length))
        return; // keeps hit_sphere's point and its unit normal
    const vec3 outward(real(x[0] / x_length), real(x[1] / x_length), real(x[2] / x_length));
    rec.point = vec3(real(wide(s.center.x) + x[0]), real(wide(s.center.y) + x[1]), real(wide(s.center.z) + x[2]));
    const wide largest_f = std::fmax(std::fabs(f[0]), std::fmax(std::fabs(f[1]), std::fabs(f[2])));
    const wide largest_c = std::fmax(std::fabs(wide(s.center.x)),
                                     std::fmax(std::fabs(wide(s.center.y)), std::fabs(wide(s.center.z))));
    const wide wide_error = 16 * (std::numeric_limits<wide>::epsilon() / 2) * (largest_f + R + largest_c);
    const vec3 x_real = vec3(real(x[0]), real(x[1]), real(x[2]));
    rec.point_error =
        gamma_n(5) * glm::abs(x_real) + gamma_n(1) * glm::abs(rec.point) + vec3(next_up(real(wide_error)));
    rec.front_face = dw[0] * x[0] + dw[1] * x[1] + dw[2] * x[2] <= 0;
    rec.geometric_normal = rec.front_face ? outward : -outward;
    rec.normal = rec.geometric_normal;
}

} // namespace detail

/// The closest hit of one shape in [tmin, tmax], by the library's robust
/// methods (rt::hit_sphere, the watertight test for triangles and meshes).
/// rec.shape is left to the caller.
inline bool hit_shape(const shape& item, const ray& r, real tmin, real tmax, hit_record& rec)
{
    if (const sphere* ball = std::get_if<sphere>(&item)) {
        if (!hit_sphere(*ball, r, tmin, tmax, rec))
            return false;
        detail::refine_sphere_hit(*ball, r, rec);
        return true;
    }
    if (const triangle* tri = std::get_if<triangle>(&item))
        return hit_triangle(*tri, r, tmin, tmax, rec);
    return hit_mesh(std::get<mesh>(item), r, tmin, tmax, rec);
}

} // namespace rt
