// light_sample.hpp - what one light delivers to a surface point (stage 05 on,
// rt::light_sample in light.hpp): the direction to it, the distance, the
// intensity that arrives. Point and directional lights as in Fundamentals of
// Computer Graphics, 4th ed., sec. 4.5; an area light (stage 10) as a point
// light at one point of it, random for each sample (area_light.hpp, FCG sec.
// 13.4.2).
#pragma once

#include <optional>

#include <glm/geometric.hpp>

#include "area_light.hpp"
#include "../core/config.hpp"
#include "light.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The point an area light shines from, seen from x: with random numbers xi,
/// a random point of it (area_light.hpp); without, its centre, so that stages
/// 05-09 see an area light as a point light there. A point inside a sphere
/// light (where no cone of directions covers it) sees it from its centre too.
inline vec3 area_light_point(const light& source, const vec3& x, const std::optional<vec2>& xi)
{
    if (source.kind == light_kind::rect)
        return xi ? sample_rect_light(source.position, source.edge1, source.edge2, xi->x, xi->y)
                  : source.position + real(0.5) * (source.edge1 + source.edge2);
    const vec3 from_center = x - source.position;
    const bool outside = glm::dot(from_center, from_center) > source.radius * source.radius;
    return xi && outside ? sample_sphere_light(source.position, source.radius, x, xi->x, xi->y) : source.position;
}

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
