// sphere.hpp - a sphere |x - c| = R and two ways to intersect a ray with it (stage 03).
//
// Substituting the ray r(t) = p + t d into |x - c|^2 = R^2 gives a quadratic in
// t whose roots are (Fundamentals of Computer Graphics, 4th ed., sec. 4.4.1,
// with the book's e written p, as the course does):
//     t = ( -d.(p - c) +- sqrt( (d.(p - c))^2 - (d.d)((p - c).(p - c) - R^2) ) ) / (d.d)
// Taken literally in float this fails far from the sphere: the two products
// under the root are both about |p - c|^2 |d|^2 and their difference, about
// (R^2 - h^2)|d|^2 for a ray passing at distance h from c, drowns in their
// rounding error. At distance 1e4 a unit sphere's discriminant is noise in
// float: rays that hit it miss, rays that pass it hit, and the depth of the
// rest is off by about R (docs/stages/03-sphere.md has the table that
// tests/stage03_sphere.cpp measures).
//
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
#include <cstdio>
#include <string>
#include <type_traits>

#include "hit_record.hpp"
#include "ray.hpp"
#include "rounding.hpp"
#include "vec.hpp"

namespace rt {

struct sphere {
    vec3 center{0};     ///< c
    real radius = 1;    ///< R
    int material = -1;  ///< index into scene::materials; -1: the default material
};

/// The smallest radius rt represents for a sphere centred at c: 16 u max|c_k|
/// (u the unit roundoff), that is, about 8 units in the last place of the
/// centre's largest coordinate. The coordinates of points near c are spaced
/// that coarsely, so a smaller sphere's hit points round onto a handful of
/// grid points around its centre, or onto the centre itself: a radius of
/// 7.1e-4 at a centre near 4e5 (a float ulp there is 0.031) gave hit points
/// equal to the centre and a (nan, nan, nan) normal (issue 19). The scene
/// loader refuses such spheres (sphere_fits_its_position); hit_sphere still
/// returns a unit normal for them.
inline real smallest_sphere_radius(const vec3& c)
{
    const real largest = std::fmax(std::fabs(c.x), std::fmax(std::fabs(c.y), std::fabs(c.z)));
    return 16 * unit_roundoff * largest;
}

/// Whether rt can represent the sphere at its position: a radius of at least
/// smallest_sphere_radius(center), and finite.
inline bool sphere_fits_its_position(const sphere& s)
{
    return std::isfinite(s.radius) && s.radius >= smallest_sphere_radius(s.center) && s.radius > 0;
}

namespace detail {

inline std::string short_number(double x)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", x);
    return text;
}

} // namespace detail

/// The parts of the loader's one-line message for a sphere that does not fit
/// its position: what was expected, what was found, and the hint.
inline std::string sphere_radius_expected(const sphere& s)
{
    return "a radius of at least " + detail::short_number(double(smallest_sphere_radius(s.center))) +
           " for a sphere centred at (" + detail::short_number(double(s.center.x)) + ", " +
           detail::short_number(double(s.center.y)) + ", " + detail::short_number(double(s.center.z)) +
           ") (8 units in the last place of its largest coordinate)";
}

inline std::string sphere_radius_found(const sphere& s)
{
    return "radius " + detail::short_number(double(s.radius));
}

constexpr const char* sphere_scale_hint =
    "the sphere is smaller than the rounding of its centre; move the scene nearer the origin, enlarge the "
    "sphere, or build with -DRT_USE_DOUBLE=ON";

/// The textbook quadratic, exactly as the course gives it: the nearest root t
/// in [tmin, tmax]; fills the hit record (point, outward normal turned towards
/// the ray, front_face, material) and leaves it untouched on a miss. Kept for
/// teaching and for comparison; the library uses hit_sphere.
inline bool hit_sphere_textbook(const sphere& s, const ray& r, real tmin, real tmax, hit_record& rec)
{
    // RT_EXERCISE_BEGIN(stage03: ray-sphere intersection)
    const vec3& p = r.origin;
    const vec3& d = r.direction;
    const vec3& c = s.center;
    const real R = s.radius;
    const vec3 pc = p - c;
    const real dd = glm::dot(d, d);
    const real dpc = glm::dot(d, pc);
    const real discriminant = dpc * dpc - dd * (glm::dot(pc, pc) - R * R);
    if (discriminant < 0)
        return false;
    const real root = std::sqrt(discriminant);
    real t = (-dpc - root) / dd;
    if (!(tmin <= t && t <= tmax)) { // written so that a NaN t (d = 0) is rejected too
        t = (-dpc + root) / dd;
        if (!(tmin <= t && t <= tmax))
            return false;
    }
    rec.t = t;
    rec.point = r.at(t);
    const vec3 outward = (rec.point - c) / R; // the unit normal of a sphere (FCG sec. 4.4.1)
    rec.front_face = glm::dot(d, outward) <= 0; // a tangent ray counts as hitting the outside
    rec.geometric_normal = rec.front_face ? outward : -outward;
    rec.normal = rec.geometric_normal;
    rec.material = s.material;
    rec.primitive = 0;
    rec.b1 = rec.b2 = 0;
    return true;
    // RT_EXERCISE_END
}

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
/// [tmin, tmax], and the hit record as hit_sphere_textbook fills it (untouched
/// on a miss). The normal is normalize(point - c) rather than (point - c) / R,
/// so it is unit length even where the computed point is an ulp off the
/// surface; where the point rounds onto the centre (a sphere smaller than
/// smallest_sphere_radius), it is -d / |d|, a unit normal facing the ray
/// rather than NaN. (The scene-level intersection, intersect.hpp, then
/// recomputes point and normal accurately: refine_sphere_hit.)
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
    rec.t = t;
    rec.point = r.at(t);
    const vec3 local = rec.point - s.center;
    const real length2 = glm::dot(local, local);
    const vec3 outward = length2 > 0 && std::isfinite(length2) ? glm::normalize(local) : -glm::normalize(r.direction);
    rec.front_face = glm::dot(r.direction, outward) <= 0;
    rec.geometric_normal = rec.front_face ? outward : -outward;
    rec.normal = rec.geometric_normal;
    rec.material = s.material;
    rec.primitive = 0;
    rec.b1 = rec.b2 = 0;
    return true;
}

} // namespace rt
