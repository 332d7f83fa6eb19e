// vec.hpp - points, directions and colors.
//
// GLM gives the vector algebra (dot, cross, normalize, length); rt only names
// the types. Points and directions use rt::real; colors are always linear RGB
// floats (the course: "RGB floats internally, RGB bytes stored").
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "config.hpp"

namespace rt {

using vec2 = glm::vec<2, real, glm::defaultp>;
using vec3 = glm::vec<3, real, glm::defaultp>;

/// Linear RGB radiance or reflectance, one float per channel.
using color = glm::vec3;

} // namespace rt
