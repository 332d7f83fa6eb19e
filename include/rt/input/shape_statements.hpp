// shape_statements.hpp - the shape statements of a scene file: sphere,
// triangle and mesh (scene_loader.hpp reads the file; docs/scene-format.md
// describes them). Each refuses what the intersection tests cannot trace.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>

#include "../core/error.hpp"
#include "material_statement.hpp"
#include "../scene/mesh.hpp"
#include "obj_check.hpp"
#include "obj_loader.hpp"
#include "../system/path_text.hpp"
#include "../scene/scene.hpp"
#include "scene_statement.hpp"
#include "../scene/sphere_shape.hpp"
#include "../scene/triangle_shape.hpp"
#include "../core/vec.hpp"

namespace rt {
namespace detail {

/// Where a scene file's mesh path leads: relative to the scene file's folder
/// (never to the working directory), or as written when absolute.
inline std::filesystem::path mesh_path(const std::filesystem::path& folder, const std::filesystem::path& written)
{
    return written.is_absolute() ? written : folder / written;
}

/// Reads `sphere center xyz radius r [material name]`.
inline sphere read_sphere(statement& line, const scene& scene_so_far)
{
    sphere s;
    line.options({"center", "radius", "material"}, [&](const std::string& option) {
        if (option == "center")
            s.center = line.vector("center");
        else if (option == "radius") {
            const source_location where = line.here();
            s.radius = line.number("radius");
            if (!(s.radius > 0))
                throw make_error(where, "a positive radius", std::to_string(s.radius),
                                 "a sphere's radius is its size, not a direction");
        } else
            s.material = find_material(scene_so_far, line);
    });
    if (!sphere_fits_its_position(s)) // sphere_shape.hpp
        throw make_error(line.here(), sphere_radius_expected(s), sphere_radius_found(s), sphere_scale_hint);
    return s;
}

/// Reads `triangle a b c [material name]`; corners beyond +-max_coordinate are refused.
inline triangle read_triangle(statement& line, const scene& scene_so_far, double max_coordinate)
{
    const source_location where = line.here();
    triangle tri;
    vec3* corners[3] = {&tri.a, &tri.b, &tri.c};
    for (int k = 0; k < 3; ++k) {
        const source_location at = line.here();
        *corners[k] = line.vector(std::string("corner ") + "abc"[k]);
        // the OBJ reader's limit: beyond it the triangle tests' products
        // overflow float and every ray misses the triangle
        const vec3& p = *corners[k];
        const real largest = std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
        if (!(double(largest) <= max_coordinate))
            throw make_error(at, std::string("a corner ") + "abc"[k] + " within +-" +
                                     detail::short_number(max_coordinate),
                             "a coordinate of " + detail::short_number(double(largest)),
                             "float arithmetic cannot trace coordinates that large; use smaller units");
    }
    if (triangle_normal(tri.a, tri.b, tri.c) == vec3(0)) // the library's normal (triangle_shape.hpp)
        throw make_error(where, "a triangle with non-zero area", "three corners on one line",
                         "check the corners");
    line.options({"material"}, [&](const std::string&) { tri.material = find_material(scene_so_far, line); });
    return tri;
}

/// Reads `mesh path [material name] [scale s] [translate xyz]` into `s`: the
/// mesh, and the materials of its MTL file unless a material is given.
/// `triangles` counts the triangles of the scene's meshes so far: one budget,
/// obj.max_triangles, for all of them.
inline void read_mesh(statement& line, scene& s, const std::filesystem::path& folder, const obj_limits& obj,
                      std::size_t& triangles)
{
    const source_location where = line.here();
    const std::filesystem::path relative = utf8_path(line.word("an OBJ file path"));
    int material_index = -2; // -2: keep the materials of the OBJ's MTL file
    real scale = 1;
    vec3 translate(0);
    line.options({"material", "scale", "translate"}, [&](const std::string& option) {
        if (option == "material")
            material_index = find_material(s, line);
        else if (option == "scale") {
            const source_location at = line.here();
            scale = line.number("scale");
            if (!(scale > 0))
                throw make_error(at, "a positive scale", std::to_string(scale));
        } else
            translate = line.vector("translate");
    });
    const std::filesystem::path path = mesh_path(folder, relative);
    obj_limits limits = obj; // one budget of triangles for all the scene's meshes
    limits.max_triangles -= triangles;
    obj_result loaded;
    try {
        loaded = load_obj(path, limits);
    } catch (const error& e) {
        throw make_error(where, "a loadable OBJ mesh", "an error", e.what());
    }
    mesh& m = loaded.geometry;
    if (m.triangles.empty())
        throw make_error(where, "a mesh with at least one triangle",
                         m.dropped_degenerate > 0 ? "only " + std::to_string(m.dropped_degenerate) +
                                                        " degenerate (zero-area) triangle(s)"
                                                  : "no faces",
                         "check the OBJ file " + found_text(utf8_text(relative)));
    triangles += m.triangles.size();
    m.source = utf8_text(relative);
    for (vec3& p : m.positions) {
        p = p * scale + translate;
        // the OBJ reader's limit holds after scale and translate too: beyond it
        // the triangle tests' products overflow and the mesh would vanish
        const real largest = std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
        if (!(double(largest) <= obj.max_coordinate))
            throw make_error(where, "a mesh within +-" + detail::short_number(obj.max_coordinate) +
                                        " after its scale and translate",
                             "a vertex at " + detail::short_number(double(largest)),
                             "float arithmetic cannot trace coordinates that large; use a smaller scale");
    }
    if (material_index != -2) {
        m.material = material_index;
        m.face_materials.clear();
    } else {
        const int offset = int(s.materials.size());
        for (int& id : m.face_materials)
            id = id < 0 ? -1 : id + offset;
        s.materials.insert(s.materials.end(), loaded.materials.begin(), loaded.materials.end());
    }
    s.shapes.emplace_back(std::move(m));
}

} // namespace detail
} // namespace rt
