// obj_loader.hpp - Wavefront OBJ meshes through tinyobjloader (stage 04).
//
// What is read (the formats of Wavefront's Advanced Visualizer documentation,
// "Object Files (.obj)" and "Material Library Files (.mtl)"):
//   v x y z            a position (extra numbers, such as vertex colors, are allowed and ignored)
//   vn x y z           a normal          vt u [v [w]]   a texture coordinate
//   f v[/vt][/vn] ...  a polygon of 3 or more corners; indices count from 1 in
//                      order of appearance, a negative index counts back from the
//                      latest element (-1 is the last one so far)
//   mtllib a.mtl       material libraries, beside the OBJ file
//   usemtl name        the material of the faces that follow
// and in an MTL file: newmtl name, Ka/Kd/Ks r [g b], Ns exponent, illum model.
// Everything else (groups, smoothing, texture maps, curves) is ignored.
//
// How: the file is read once into memory and checked line by line here, so
// that every problem is one line "file:line:col: expected ..., found ...;
// hint" (tinyobjloader reads a bad number as 0, drops faces with bad indices
// with a warning and does not say where). The positions are taken from this
// check, parsed at the precision of rt::real (Debian's tinyobjloader is built
// with float). tinyobjloader (Debian's libtinyobjloader, linked through rt::rt)
// then parses the faces, with its triangulation off (it split a concave quad
// along its shorter diagonal even when that lies outside, and got 60 of 300
// random simple 5- to 9-gons wrong: tests/library_triangulate.cpp); rt cuts
// each face of 4 or more corners itself (triangulate.hpp). A face that is not
// a simple polygon (edges crossing) is cut as a fan from its first corner with
// a warning; repeated consecutive corners are merged (each counted as a
// dropped degenerate triangle). The MTL files are parsed here and handed to
// tinyobjloader by name, so usemtl picks the same materials in both.
//
// Text: a UTF-8 byte order mark is skipped, lines end at LF, CR LF or CR, and
// a '\' at the end of a line continues it on the next (for_each_line);
// tinyobjloader reads the text so normalised, so the lines it reads are the
// lines checked here and every message keeps the file's line numbers.
//
// What loading can do without is a warning, one line per kind
// "file:line:col: warning: expected ..., found ... (and N more like it); hint"
// on obj_limits::warnings (std::cerr), and an error with obj_limits::strict
// (the programs' --strict): a material library that does not exist (its
// materials: the default material), usemtl without mtllib, of a name no
// library declares or of no name (the default material), a face that is not
// simple, a corner "v/vt/" whose normal slot is empty (read as "v/vt"; the two
// last appear in files that Blender and trimesh load).
//
// The check also keeps tinyobjloader (2.0.0rc10) away from what it cannot
// read safely (docs/reliability.md, "Decisions"): every number, also in the
// statements rt ignores, must fit a float, with an exponent from -400 to 400
// and at most 300 digits; a skin-weight joint id ("vw") must be from 0 to
// 2^30; a tag ("t") may claim no more values than its line holds; a face has
// at most obj_limits::max_face_corners corners; an MTL file is read once
// however it is spelled. A coordinate must be within +-obj_limits::max_coordinate
// (1e18), beyond which float arithmetic cannot trace a triangle.
//
// The mesh stores only what the file provides: normals (texture coordinates)
// only when the faces refer to them. Zero-area triangles are dropped and
// counted in mesh::dropped_degenerate. MTL colors map to rt::material: Ka ka
// (kd when absent, as in scene files), Kd kd, Ks ks, Ns p, Ke emission, and
// for the illumination models "reflection on, ray trace on" (illum 3 and 5) km = Ks.
// Names (newmtl, usemtl) are one word, as tinyobjloader reads them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <sstream>
#include <streambuf>
#include <string>
#include <utility>
#include <vector>

#include <tiny_obj_loader.h>

#include "../core/error.hpp"
#include "../scene/material.hpp"
#include "../scene/mesh.hpp"
#include "mtl_reader.hpp"
#include "obj_check.hpp"
#include "../system/path_text.hpp"
#include "text_file.hpp"
#include "triangulate.hpp"

namespace rt {

/// What loading an OBJ file gives: the mesh and the materials of its MTL files
/// (mesh::face_materials index into `materials`).
struct obj_result {
    mesh geometry;
    std::vector<material> materials;
    std::size_t polygons = 0;  ///< face statements in the file (before triangulation)
};

namespace detail {

/// A read-only stream over text already in memory.
class memory_buffer : public std::streambuf {
public:
    explicit memory_buffer(std::string& text) { setg(text.data(), text.data(), text.data() + text.size()); }
};

} // namespace detail

/// Loads an OBJ file (and the MTL files it names, from its folder). Throws
/// rt::error with file:line:col for a missing, unreadable or malformed file.
inline obj_result load_obj(const std::filesystem::path& path, const obj_limits& limits = {})
{
    const std::string name = detail::utf8_text(path);
    const std::string text = detail::read_text(path, "an OBJ", limits.max_bytes, {});
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    std::vector<detail::mtl_entry> mtl;
    detail::obj_warnings warnings(limits);
    // tinyobjloader reads the lines as the check read them: without a byte
    // order mark, line breaks made LF, continued lines joined
    std::string normalised;
    detail::obj_check checked = detail::check_obj(text, name, folder, limits, mtl, warnings, normalised);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> groups;
    std::vector<tinyobj::material_t> tiny_materials;
    std::string warning, failure;
    detail::memory_buffer buffer(normalised);
    std::istream stream(&buffer);
    detail::mtl_names_reader names(mtl);
    // triangulate = false: tinyobjloader only parses; rt triangulates (triangulate.hpp)
    if (!tinyobj::LoadObj(&attrib, &groups, &tiny_materials, &warning, &failure, &stream, &names, false, false)) {
        // not reached after the check above (which refuses all that tinyobjloader
        // does); its own text has no place and may be wrong, so it is not shown
        throw error(source_location{name}, "expected an OBJ file tinyobjloader can read, found one it refuses "
                                           "though rt's check passed it; please report this file");
    }

    obj_result result;
    result.polygons = checked.polygons;
    mesh& m = result.geometry;
    m.source = name;
    m.read_from.push_back(path);
    m.read_from.insert(m.read_from.end(), checked.libraries.begin(), checked.libraries.end());
    m.positions = std::move(checked.positions);
    for (const detail::mtl_entry& entry : mtl) {
        material mat = entry.value;
        if (!entry.has_ka)
            mat.ka = mat.kd; // as in scene files
        if (!entry.has_ns)
            mat.p = material{}.p;
        mat.km = (entry.illum == 3 || entry.illum == 5) ? mat.ks : color(0.0f); // reflection on
        result.materials.push_back(mat);
    }

    const std::size_t normal_count = attrib.normals.size() / 3;
    const std::size_t texcoord_count = attrib.texcoords.size() / 2;
    const std::size_t vertex_count = m.positions.size();
    bool any_normal = false, any_texcoord = false, any_material = false;
    std::vector<index3> normal_indices, texcoord_indices;
    std::vector<int> face_materials;
    std::size_t face_number = 0, polygon_number = 0;
    std::vector<vec3> polygon;
    std::vector<corner3> pieces;
    for (const tinyobj::shape_t& group : groups) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < group.mesh.num_face_vertices.size(); ++f) {
            // the corner count from the check: tinyobjloader keeps it in an unsigned char
            const std::size_t corners =
                face_number < checked.face_corners.size() ? checked.face_corners[face_number++] : 0;
            if (corners % 256 != group.mesh.num_face_vertices[f] || offset + corners > group.mesh.indices.size())
                throw error(source_location{name}, "expected the faces rt's check counted, found others in "
                                                   "tinyobjloader's result; please report this file");
            const std::size_t first = offset;
            offset += corners;
            pieces.clear();
            if (corners == 3) {
                pieces.push_back({0, 1, 2});
            } else {
                polygon.clear();
                bool inside = true;
                for (std::size_t k = 0; k < corners; ++k) {
                    const int index = group.mesh.indices[first + k].vertex_index;
                    inside = inside && index >= 0 && std::size_t(index) < vertex_count;
                    polygon.push_back(inside ? m.positions[std::size_t(index)] : vec3(0));
                }
                const source_location at =
                    polygon_number < checked.polygon_at.size()
                        ? source_location{name, checked.polygon_at[polygon_number].first,
                                          checked.polygon_at[polygon_number].second}
                        : source_location{name};
                ++polygon_number;
                if (!inside) // cannot happen after the check above; never index out of range
                    continue;
                polygon_triangulation cut = triangulate_polygon(polygon);
                if (cut.problem == polygon_problem::not_simple)
                    warnings.add(detail::obj_warnings::not_simple, at, "a simple polygon",
                                 "a face of " + std::to_string(corners) + " corners with " + to_string(cut.problem),
                                 "it is cut into a fan from its first corner; check the face in a modelling program");
                m.dropped_degenerate += corners - 2 - cut.triangles.size(); // repeated corners merged
                pieces = std::move(cut.triangles);
            }
            for (const corner3& piece : pieces) {
                index3 position{}, normal{}, texcoord{};
                bool valid = true;
                for (std::size_t k = 0; k < 3; ++k) {
                    const tinyobj::index_t& index = group.mesh.indices[first + piece[k]];
                    valid = valid && index.vertex_index >= 0 && std::size_t(index.vertex_index) < vertex_count;
                    position[k] = std::uint32_t(index.vertex_index);
                    const bool has_normal = index.normal_index >= 0 && std::size_t(index.normal_index) < normal_count;
                    const bool has_texcoord =
                        index.texcoord_index >= 0 && std::size_t(index.texcoord_index) < texcoord_count;
                    normal[k] = has_normal ? std::uint32_t(index.normal_index) : no_index;
                    texcoord[k] = has_texcoord ? std::uint32_t(index.texcoord_index) : no_index;
                }
                if (!valid) // cannot happen after the check above; never index out of range
                    continue;
                const vec3& a = m.positions[position[0]];
                const vec3& b = m.positions[position[1]];
                const vec3& c = m.positions[position[2]];
                if (!(glm::length(glm::cross(b - a, c - a)) > 0)) {
                    ++m.dropped_degenerate;
                    continue;
                }
                m.triangles.push_back(position);
                normal_indices.push_back(normal);
                texcoord_indices.push_back(texcoord);
                any_normal = any_normal || normal[0] != no_index || normal[1] != no_index || normal[2] != no_index;
                any_texcoord =
                    any_texcoord || texcoord[0] != no_index || texcoord[1] != no_index || texcoord[2] != no_index;
                const int id = f < group.mesh.material_ids.size() ? group.mesh.material_ids[f] : -1;
                face_materials.push_back(id >= 0 && std::size_t(id) < result.materials.size() ? id : -1);
                any_material = any_material || face_materials.back() >= 0;
            }
        }
    }
    warnings.flush();
    if (any_normal) {
        m.normals.reserve(normal_count);
        for (std::size_t i = 0; i < normal_count; ++i)
            m.normals.emplace_back(real(attrib.normals[3 * i]), real(attrib.normals[3 * i + 1]),
                                   real(attrib.normals[3 * i + 2]));
        m.normal_indices = std::move(normal_indices);
    }
    if (any_texcoord) {
        m.texcoords.reserve(texcoord_count);
        for (std::size_t i = 0; i < texcoord_count; ++i)
            m.texcoords.emplace_back(real(attrib.texcoords[2 * i]), real(attrib.texcoords[2 * i + 1]));
        m.texcoord_indices = std::move(texcoord_indices);
    }
    if (any_material)
        m.face_materials = std::move(face_materials);
    return result;
}

/// Requires that a loaded OBJ file has a triangle to trace: the one message of
/// every program that renders a bare OBJ file (a file of comments only, or of
/// zero-area faces only, would give a black image).
inline void require_triangles(const obj_result& loaded)
{
    const mesh& m = loaded.geometry;
    if (!m.triangles.empty())
        return;
    throw error(source_location{m.source},
                "expected a model with at least one triangle, found " +
                    (m.dropped_degenerate > 0
                         ? "only " + std::to_string(m.dropped_degenerate) + " degenerate (zero-area) triangle(s)"
                         : std::string("no faces")) +
                    "; check the OBJ file");
}

/// One line describing a loaded OBJ file, for a program to print.
inline std::string summary(const obj_result& loaded)
{
    const mesh& m = loaded.geometry;
    std::ostringstream out;
    out << m.source << ": " << m.triangles.size() << " triangles from " << loaded.polygons << " faces, "
        << m.positions.size() << " vertices, " << (m.normals.empty() ? "no" : std::to_string(m.normals.size()))
        << " normals, " << (m.texcoords.empty() ? "no" : std::to_string(m.texcoords.size()))
        << " texture coordinates, " << loaded.materials.size() << " materials, " << m.dropped_degenerate
        << " degenerate triangles dropped";
    return out.str();
}

} // namespace rt
