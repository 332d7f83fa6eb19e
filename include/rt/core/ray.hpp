// ray.hpp - a half line r(t) = p + t d.
//
// Fundamentals of Computer Graphics (Shirley, Marschner), 4th ed., sec. 4.3:
// p is the origin and d the direction; d need not be unit length, so t measures
// distance in units of |d|.
#pragma once

#include <limits>

#include "vec.hpp"

namespace rt {

/// +inf as rt::real: the tmax of a ray that may go on forever.
constexpr real infinity = std::numeric_limits<real>::infinity();

struct ray {
    vec3 origin{0};    ///< p
    vec3 direction{0}; ///< d, not necessarily normalised

    /// The point at parameter t: p + t d.
    vec3 at(real t) const { return origin + t * direction; }
};

} // namespace rt
