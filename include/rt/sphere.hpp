// sphere.hpp - a sphere |x - c| = R (stage 03).
#pragma once

#include "vec.hpp"

namespace rt {

struct sphere {
    vec3 center{0};     ///< c
    real radius = 1;    ///< R
    int material = -1;  ///< index into scene::materials; -1: the default material
};

} // namespace rt
