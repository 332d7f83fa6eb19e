// sphere_stable.hpp - the library's ray-sphere intersection: the stable method.
//
// The textbook quadratic (sphere.hpp, the stage-03 exercise) fails in float far
// from the sphere, where the discriminant drowns in rounding error.
// The stable method (Haines, Guenther, Akenine-Moller, "Precision Improvements
// for Ray/Sphere Intersection", Ray Tracing Gems, 2019, ch. 7) rewrites both
// steps; with f = p - c, a = d.d, b = f.d (half the usual b), c = f.f - R^2:
//   1. the discriminant from the perpendicular vector from c to the ray's line,
//          b^2 - a c = a (R^2 - |f - (f.d^)d^|^2),   d^ = d / |d|,
//      a short vector (at most R long for a hit), so nothing large cancels;
//   2. the roots from a sum of terms of one sign and the product of the roots,
//          q = -(b + sign(b) sqrt(b^2 - a c)),   t0 = c / q,   t1 = q / a.
// One change from the chapter: c = |f|^2 - R^2 itself cancels when the origin
// is close to the surface of a sphere much larger than that distance (a
// "ground" sphere of radius 1e4 seen from height 1: hundreds of ulps in
// float), so c is formed in a wider type in which the products of reals are
// exact or nearly so (pbrt, 3rd ed., sec. A.5.1, solves its quadratics in
// double for the same reason).
#pragma once

#include <cmath>
#include <type_traits>

#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../scene/sphere_shape.hpp"
#include "../core/vec.hpp"

namespace rt {

namespace detail {

/// A type with more precision than real, for the one term that needs it.
using wider_real = std::conditional_t<std::is_same<real, float>::value, double, long double>;

} // namespace detail

/// The roots t0 <= t1 of the ray-sphere quadratic by the stable method of Ray
/// Tracing Gems ch. 7 (see the top of this file); false when the ray's line
/// misses the sphere, or when d = 0. A tangent ray has t0 == t1.
inline bool sphere_roots_stable(const sphere& s, const ray& r, real& t0, real& t1)
{
    using wide = detail::wider_real;
    const vec3& d = r.direction;
    const real R = s.radius;
    const vec3 f = r.origin - s.center;
    const real a = glm::dot(d, d);
    const real b = glm::dot(f, d);
    const vec3 d_unit = d / std::sqrt(a);
    const vec3 perpendicular = f - glm::dot(f, d_unit) * d_unit; // from c to the closest point of the line
    const real discriminant = a * (R * R - glm::dot(perpendicular, perpendicular));
    if (!(discriminant >= 0)) // also false for NaN, from d = 0
        return false;
    const real q = -(b + std::copysign(std::sqrt(discriminant), b));
    if (q == 0) { // b = 0 and a tangent line: the origin is the point of contact
        t0 = t1 = 0;
        return true;
    }
    // f itself in the wider type too: p - c rounded to real loses the sign of
    // c for an origin just outside a sphere far from the origin (a spawned ray)
    const wide fx = wide(r.origin.x) - wide(s.center.x);
    const wide fy = wide(r.origin.y) - wide(s.center.y);
    const wide fz = wide(r.origin.z) - wide(s.center.z);
    const wide c = fx * fx + fy * fy + fz * fz - wide(R) * R;
    t0 = real(c / q);
    t1 = q / a;
    if (t0 > t1) {
        const real swap = t0;
        t0 = t1;
        t1 = swap;
    }
    return true;
}

/// The library's default sphere intersection: the stable roots, the nearest in
/// [tmin, tmax], and the hit record filled by fill_sphere_record
/// (sphere_shape.hpp), as the stage-03 exercise fills it; untouched on a miss.
/// (The scene-level intersection, accelerator.hpp, then
/// recomputes point and normal accurately: detail::refine_sphere_hit.)
inline bool hit_sphere(const sphere& s, const ray& r, real tmin, real tmax, hit_record& rec)
{
    real t0 = 0, t1 = 0;
    if (!sphere_roots_stable(s, r, t0, t1))
        return false;
    real t = t0;
    if (!(tmin <= t && t <= tmax)) {
        t = t1;
        if (!(tmin <= t && t <= tmax))
            return false;
    }
    fill_sphere_record(s, r, t, rec);
    return true;
}

} // namespace rt
