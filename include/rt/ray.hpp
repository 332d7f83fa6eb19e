// ray.hpp - a half line r(t) = p + t d.
//
// Fundamentals of Computer Graphics (Shirley, Marschner), 4th ed., sec. 4.3:
// p is the origin and d the direction; d need not be unit length, so t measures
// distance in units of |d|.
#pragma once

#include "vec.hpp"

namespace rt {

struct ray {
    vec3 origin{0};    ///< p
    vec3 direction{0}; ///< d, not necessarily normalised

    /// The point at parameter t: p + t d.
    vec3 at(real t) const { return origin + t * direction; }
};

} // namespace rt
