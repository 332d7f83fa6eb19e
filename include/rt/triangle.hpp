// triangle.hpp - a single triangle with corners a, b, c (stage 04).
#pragma once

#include "vec.hpp"

namespace rt {

struct triangle {
    vec3 a{0}, b{0}, c{0};  ///< corners, counter-clockwise seen from the front
    int material = -1;      ///< index into scene::materials; -1: the default material
};

} // namespace rt
