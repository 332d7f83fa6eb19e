// light_statement.hpp - the light statement of a scene file: point,
// directional, rect and sphere lights (scene_loader.hpp reads the file;
// docs/scene-format.md describes it).
#pragma once

#include <string>

#include <glm/geometric.hpp>

#include "../core/error.hpp"
#include "../scene/light.hpp"
#include "scene_statement.hpp"
#include "../core/vec.hpp"

namespace rt {
namespace detail {

/// Reads `light point|directional|rect|sphere ...` and its options.
inline light read_light(statement& line)
{
    const std::string kind = line.word("a light type (point, directional, rect or sphere)");
    light l;
    if (kind == "point") {
        l.kind = light_kind::point;
        line.options({"position", "intensity"}, [&](const std::string& option) {
            if (option == "position")
                l.position = line.vector("position");
            else
                l.intensity = line.rgb("intensity");
        });
    } else if (kind == "directional") {
        l.kind = light_kind::directional;
        line.options({"direction", "intensity"}, [&](const std::string& option) {
            if (option == "direction")
                l.direction = line.direction("direction");
            else
                l.intensity = line.rgb("intensity");
        });
    } else if (kind == "rect") {
        l.kind = light_kind::rect;
        line.options({"corner", "edge1", "edge2", "intensity"}, [&](const std::string& option) {
            if (option == "corner")
                l.position = line.vector("corner");
            else if (option == "edge1")
                l.edge1 = line.vector("edge1");
            else if (option == "edge2")
                l.edge2 = line.vector("edge2");
            else
                l.intensity = line.rgb("intensity");
        });
        const real area = glm::length(glm::cross(l.edge1, l.edge2));
        if (!(area > 0))
            throw make_error(line.line_start(), "a rect light with an area", "edges that are parallel or zero",
                             "edge1 and edge2 are two sides from the corner, e.g. edge1 1 0 0 edge2 0 0 1");
    } else if (kind == "sphere") {
        l.kind = light_kind::sphere;
        line.options({"center", "radius", "intensity"}, [&](const std::string& option) {
            if (option == "center")
                l.position = line.vector("center");
            else if (option == "radius") {
                const source_location where = line.here();
                l.radius = line.number("radius");
                if (!(l.radius > 0))
                    throw make_error(where, "a positive radius", detail::short_number(double(l.radius)),
                                     "a light of radius 0 is a point light: use light point");
            } else
                l.intensity = line.rgb("intensity");
        });
    } else {
        throw make_error(line.last(), "a light type (point, directional, rect or sphere)", found_text(kind),
                         nearest_hint(kind, {"point", "directional", "rect", "sphere"}));
    }
    return l;
}

} // namespace detail
} // namespace rt
