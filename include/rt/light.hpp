// light.hpp - point and directional lights (used from stage 05 on).
//
// A point light shines from a position in every direction; a directional light
// shines along one direction from infinitely far away (Fundamentals of Computer
// Graphics, 4th ed., sec. 4.5). Both have an RGB intensity I.
#pragma once

#include "vec.hpp"

namespace rt {

enum class light_kind { point, directional };

struct light {
    light_kind kind = light_kind::point;
    vec3 position{0, 10, 0};   ///< point lights: where the light is
    vec3 direction{0, -1, 0};  ///< directional lights: the direction light travels
    color intensity{1.0f};     ///< I
};

} // namespace rt
