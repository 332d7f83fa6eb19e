// material.hpp - how a surface reflects light (used from stage 05 on).
//
// Blinn-Phong with an ideal mirror term, Fundamentals of Computer Graphics,
// 4th ed., sec. 4.5-4.8: ambient ka, diffuse kd, specular ks with Phong
// exponent p, and mirror reflectance km. Defaults are those of
// docs/scene-format.md: a matte light grey.
#pragma once

#include <string>

#include "vec.hpp"

namespace rt {

struct material {
    std::string name = "default";
    color ka{0.8f};  ///< ambient reflectance (the scene file defaults it to kd)
    color kd{0.8f};  ///< diffuse reflectance
    color ks{0.0f};  ///< specular reflectance
    real p = 32;     ///< Phong exponent of the specular highlight
    color km{0.0f};  ///< mirror reflectance
};

} // namespace rt
