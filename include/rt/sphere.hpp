// sphere.hpp - a sphere |x - c| = R and two ways to intersect a ray with it (stage 03).
//
// Substituting r(t) = p + t d into |x - c|^2 = R^2 gives a quadratic in t
// (Fundamentals of Computer Graphics, 4th ed., sec. 4.4.1, eq. 4.2 / the course):
//     t = ( -d.(p - c) +- sqrt( (d.(p - c))^2 - (d.d)((p - c).(p - c) - R^2) ) ) / (d.d)
// Taken literally in float this fails far from the sphere: the two products
// under the root are both about |p - c|^2 |d|^2 and their difference, about
// R^2 |d|^2, drowns in their rounding error (at distance 1e4 a unit sphere's
// discriminant is already noise; at 1e6 it is lost and the ray misses).
//
// The stable method (Haines, Guenther, Akenine-Moller, "Precision Improvements
// for Ray/Sphere Intersection", Ray Tracing Gems, 2019, ch. 7, eqs. 7.5-7.8):
//     f = p - c, a = d.d, b = f.d (the half coefficient), c = f.f - R^2
//     discriminant from the perpendicular distance: b^2 - a c = a (R^2 - |f - (f.d^)d^|^2)
//     q = -(b + sign(b) sqrt(b^2 - a c)),  t0 = c / q,  t1 = q / a
// avoids both cancellations: the discriminant is formed from a short vector,
// and the two roots are taken from a sum of same-signed terms.
#pragma once

#include <cmath>

#include "hit_record.hpp"
#include "ray.hpp"
#include "vec.hpp"

namespace rt {

struct sphere {
    vec3 center{0};     ///< c
    real radius = 1;    ///< R
    int material = -1;  ///< index into scene::materials; -1: the default material
};

/// The textbook quadratic, exactly as the course gives it: the nearest root t
/// in [tmin, tmax]; fills the hit record (point, outward normal turned towards
/// the ray, front_face, material). Kept for teaching and for comparison.
inline bool hit_sphere_textbook(const sphere& s, const ray& r, real tmin, real tmax, hit_record& rec)
{
    // RT_EXERCISE_BEGIN(stage03: ray-sphere intersection)
    const vec3& p = r.origin;
    const vec3& d = r.direction;
    const vec3 pc = p - s.center;
    const real dd = glm::dot(d, d);
    const real dpc = glm::dot(d, pc);
    const real discriminant = dpc * dpc - dd * (glm::dot(pc, pc) - s.radius * s.radius);
    if (discriminant < 0)
        return false;
    const real root = std::sqrt(discriminant);
    real t = (-dpc - root) / dd;
    if (t < tmin || t > tmax) {
        t = (-dpc + root) / dd;
        if (t < tmin || t > tmax)
            return false;
    }
    rec.t = t;
    rec.point = r.at(t);
    const vec3 outward = (rec.point - s.center) / s.radius;
    rec.front_face = glm::dot(d, outward) < 0;
    rec.geometric_normal = rec.front_face ? outward : -outward;
    rec.normal = rec.geometric_normal;
    rec.material = s.material;
    rec.primitive = 0;
    rec.b1 = rec.b2 = 0;
    return true;
    // RT_EXERCISE_END
}

/// The roots t0 <= t1 of the ray-sphere quadratic by the stable method of Ray
/// Tracing Gems ch. 7 (see the top of this file); false when the ray misses.
inline bool sphere_roots_stable(const sphere& s, const ray& r, real& t0, real& t1)
{
    const vec3 f = r.origin - s.center;
    const vec3& d = r.direction;
    const real a = glm::dot(d, d);
    const real b = glm::dot(f, d);
    const real c = glm::dot(f, f) - s.radius * s.radius;
    const vec3 d_unit = d / std::sqrt(a);
    const vec3 perpendicular = f - glm::dot(f, d_unit) * d_unit; // f minus its part along d
    const real discriminant = a * (s.radius * s.radius - glm::dot(perpendicular, perpendicular));
    if (discriminant < 0)
        return false;
    const real q = -(b + std::copysign(std::sqrt(discriminant), b));
    if (q == 0) { // b = 0 and a tangent ray: one double root at t = 0 ... or c = 0 too
        t0 = t1 = 0;
        return c == 0;
    }
    t0 = c / q;
    t1 = q / a;
    if (t0 > t1) {
        const real swap = t0;
        t0 = t1;
        t1 = swap;
    }
    return true;
}

/// The library's default sphere intersection: the stable roots, the nearest in
/// [tmin, tmax], and the hit record as hit_sphere_textbook fills it.
inline bool hit_sphere(const sphere& s, const ray& r, real tmin, real tmax, hit_record& rec)
{
    real t0 = 0, t1 = 0;
    if (!sphere_roots_stable(s, r, t0, t1))
        return false;
    real t = t0;
    if (t < tmin || t > tmax) {
        t = t1;
        if (t < tmin || t > tmax)
            return false;
    }
    rec.t = t;
    rec.point = r.at(t);
    const vec3 outward = (rec.point - s.center) / s.radius;
    rec.front_face = glm::dot(r.direction, outward) < 0;
    rec.geometric_normal = rec.front_face ? outward : -outward;
    rec.normal = rec.geometric_normal;
    rec.material = s.material;
    rec.primitive = 0;
    rec.b1 = rec.b2 = 0;
    return true;
}

} // namespace rt
