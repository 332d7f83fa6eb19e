// light.hpp - point, directional and area lights, as a scene declares them
// (used from stage 05 on; what one delivers to a point: light_sample.hpp).
//
// A point light shines from a position in every direction; a directional light
// shines along one direction from infinitely far away (Fundamentals of Computer
// Graphics, 4th ed., sec. 4.5). An area light (stage 10, FCG sec. 13.4.2), a
// parallelogram or a sphere, acts for each sample as a point light at a random
// point of it (area_light.hpp). Every light has an RGB intensity I.
#pragma once

#include <limits>

#include "../core/config.hpp"
#include "../core/vec.hpp"

namespace rt {

enum class light_kind { point, directional, rect, sphere };

struct light {
    light_kind kind = light_kind::point;
    vec3 position{0, 10, 0};   ///< point lights: where the light is; rect: a corner; sphere: the centre
    vec3 direction{0, -1, 0};  ///< directional lights: the direction light travels
    vec3 edge1{1, 0, 0};       ///< rect lights: the two edges from the corner
    vec3 edge2{0, 0, 1};
    real radius = 1;           ///< sphere lights
    color intensity{1.0f};     ///< I
};

/// True for the lights that have an area (stage 10): a rectangle or a sphere.
inline bool is_area_light(const light& source)
{
    return source.kind == light_kind::rect || source.kind == light_kind::sphere;
}

/// What one light delivers to a surface point x: the unit direction l from x
/// towards the light, the distance to it (infinite for a directional light),
/// and the intensity I arriving at x.
struct light_sample {
    vec3 l{0, 1, 0};
    real distance = std::numeric_limits<real>::infinity();
    color intensity{0.0f};
};

} // namespace rt
