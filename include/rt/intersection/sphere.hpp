// sphere.hpp - a sphere |x - c| = R and the textbook ray-sphere intersection (stage 03).
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
// tests/stage03_sphere.cpp measures). The library intersects spheres by the
// stable method of sphere_stable.hpp instead.
//
#pragma once

#include <cmath>

#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../scene/sphere_shape.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The textbook quadratic, exactly as the course gives it: the nearest root t
/// in the closed interval [tmin, tmax] (the smaller root if it is inside, else
/// the larger); on a hit, fills the record by calling the given
/// fill_sphere_record(s, r, t, rec) (scene/sphere_shape.hpp); on a miss returns false
/// and leaves the record untouched. A ray with d = 0 misses. Kept for
/// teaching and for comparison; the library uses hit_sphere.
inline bool hit_sphere_textbook(const sphere& s, const ray& r, real tmin, real tmax, hit_record& rec)
{
    // RT_EXERCISE_BEGIN(stage03: ray-sphere intersection)
    // Hint: solve the quadratic for the nearest root t in [tmin, tmax]; then the
    //   given fill_sphere_record(s, r, t, rec) (scene/sphere_shape.hpp) fills the record.
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
    fill_sphere_record(s, r, t, rec); // given: point, normals, front_face, material
    return true;
    // RT_EXERCISE_END
}

} // namespace rt
