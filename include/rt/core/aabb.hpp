// aabb.hpp - an axis-aligned bounding box [lo, hi].
#pragma once

#include <limits>

#include <glm/common.hpp>

#include "vec.hpp"

namespace rt {

struct aabb {
    /// An empty box: lo = +inf, hi = -inf, so that growing it by any point works.
    vec3 lo{std::numeric_limits<real>::infinity()};
    vec3 hi{-std::numeric_limits<real>::infinity()};

    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    void grow(const vec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    void grow(const aabb& box) { lo = glm::min(lo, box.lo); hi = glm::max(hi, box.hi); }
    vec3 extent() const { return hi - lo; }
    vec3 center() const { return (lo + hi) * real(0.5); }
};

} // namespace rt
