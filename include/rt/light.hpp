// light.hpp - point, directional and area lights (used from stage 05 on).
//
// A point light shines from a position in every direction; a directional light
// shines along one direction from infinitely far away (Fundamentals of Computer
// Graphics, 4th ed., sec. 4.5). An area light (stage 10, FCG sec. 13.4.2), a
// parallelogram or a sphere, acts for each sample as a point light at a random
// point of it (area_light.hpp). Every light has an RGB intensity I.
#pragma once

#include <cmath>
#include <limits>
#include <optional>

#include "area_light.hpp"
#include "vec.hpp"

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

/// The point an area light shines from, seen from x: with random numbers xi,
/// a random point of it (area_light.hpp); without, its centre, so that stages
/// 05-09 see an area light as a point light there.
inline vec3 area_light_point(const light& source, const vec3& x, const std::optional<vec2>& xi)
{
    if (source.kind == light_kind::rect)
        return xi ? sample_rect_light(source.position, source.edge1, source.edge2, xi->x, xi->y)
                  : source.position + real(0.5) * (source.edge1 + source.edge2);
    return xi ? sample_sphere_light(source.position, source.radius, x, xi->x, xi->y) : source.position;
}

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
/// physical inverse-square law. An area light is the point light at
/// area_light_point(source, x, xi).
inline light_sample sample_light(const light& source, const vec3& x, bool falloff = false,
                                 const std::optional<vec2>& xi = std::nullopt)
{
    light_sample sample;
    if (source.kind == light_kind::directional) {
        sample.l = -glm::normalize(source.direction);
        sample.intensity = source.intensity;
        return sample;
    }
    const vec3 to_light = (is_area_light(source) ? area_light_point(source, x, xi) : source.position) - x;
    sample.distance = glm::length(to_light);
    sample.l = sample.distance > 0 ? to_light / sample.distance : vec3(0, 1, 0);
    sample.intensity = source.intensity;
    if (falloff && sample.distance > 0)
        sample.intensity /= float(sample.distance * sample.distance);
    return sample;
}

} // namespace rt
