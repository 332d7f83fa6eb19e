// light.hpp - point and directional lights (used from stage 05 on).
//
// A point light shines from a position in every direction; a directional light
// shines along one direction from infinitely far away (Fundamentals of Computer
// Graphics, 4th ed., sec. 4.5). Both have an RGB intensity I.
#pragma once

#include <cmath>
#include <limits>

#include "vec.hpp"

namespace rt {

enum class light_kind { point, directional };

struct light {
    light_kind kind = light_kind::point;
    vec3 position{0, 10, 0};   ///< point lights: where the light is
    vec3 direction{0, -1, 0};  ///< directional lights: the direction light travels
    color intensity{1.0f};     ///< I
};

/// What one light delivers to a surface point x: the unit direction l from x
/// towards the light, the distance to it (infinite for a directional light),
/// and the intensity I arriving at x.
struct light_sample {
    vec3 l{0, 1, 0};
    real distance = std::numeric_limits<real>::infinity();
    color intensity{0.0f};
};

/// The light as seen from x. Point lights keep their intensity at any distance,
/// as in the book (sec. 4.5); with `falloff` they fall off as I / r^2, the
/// physical inverse-square law.
inline light_sample sample_light(const light& source, const vec3& x, bool falloff = false)
{
    light_sample sample;
    if (source.kind == light_kind::directional) {
        sample.l = -glm::normalize(source.direction);
        sample.intensity = source.intensity;
        return sample;
    }
    const vec3 to_light = source.position - x;
    sample.distance = glm::length(to_light);
    sample.l = sample.distance > 0 ? to_light / sample.distance : vec3(0, 1, 0);
    sample.intensity = source.intensity;
    if (falloff && sample.distance > 0)
        sample.intensity /= float(sample.distance * sample.distance);
    return sample;
}

} // namespace rt
