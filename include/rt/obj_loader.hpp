// obj_loader.hpp - Wavefront OBJ meshes through tinyobjloader (stage 04).
//
// tinyobjloader (Debian's libtinyobjloader, linked through rt::rt) parses the
// file; this header turns its output into an rt::mesh that stores only what the
// file provides, triangulates polygons (fans), drops zero-area triangles with a
// count, maps MTL colours to rt materials, and reports every problem as one
// line "file:line: expected ..., found ...; hint".
#pragma once

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "error.hpp"
#include "material.hpp"
#include "mesh.hpp"

namespace rt {

/// What loading an OBJ file gives: the mesh and the materials of its MTL files
/// (mesh::face_materials index into `materials`).
struct obj_result {
    mesh geometry;
    std::vector<material> materials;
};

/// Limits checked before allocating, so a hostile file cannot exhaust memory.
struct obj_limits {
    std::size_t max_triangles = std::size_t(1) << 26;  ///< 67 million
};

namespace detail {

/// The 1-based line of the `face_number`-th face statement ("f ...") of an OBJ
/// file, or 0 when it cannot be found; used only to point an error message at
/// the right line (tinyobjloader does not report face lines).
inline int obj_face_line(const std::filesystem::path& path, std::size_t face_number)
{
    std::ifstream in(path);
    std::string text;
    std::size_t faces = 0;
    for (int line = 1; std::getline(in, text); ++line) {
        std::size_t first = text.find_first_not_of(" \t");
        if (first != std::string::npos && text[first] == 'f' && first + 1 < text.size() &&
            (text[first + 1] == ' ' || text[first + 1] == '\t')) {
            if (faces == face_number)
                return line;
            ++faces;
        }
    }
    return 0;
}

/// A tinyobjloader message (possibly several lines) as one short line: line
/// breaks become blanks, other bytes that are not printable ASCII become '?'
/// (its messages quote names from the file), and it keeps its first 200
/// characters, so a message never dumps file contents.
inline std::string one_line(std::string text)
{
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
        text.pop_back();
    const std::size_t keep = 200;
    if (text.size() > keep)
        text = text.substr(0, keep) + "...";
    for (char& c : text)
        if (c == '\n' || c == '\r')
            c = ' ';
        else if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) >= 127)
            c = '?';
    return text;
}

inline color to_color(const tinyobj::real_t rgb[3])
{
    return color(float(rgb[0]), float(rgb[1]), float(rgb[2]));
}

} // namespace detail

/// Loads an OBJ file (and the MTL files it names, from its folder).
/// Throws rt::error with file:line for a missing, unreadable or malformed file.
inline obj_result load_obj(const std::filesystem::path& path, const obj_limits& limits = {})
{
    const std::string name = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw error(source_location{name}, "expected an OBJ file, found no such file; check the path");
    if (std::filesystem::is_directory(path, ec))
        throw error(source_location{name}, "expected an OBJ file, found a folder; name the .obj file itself");
    if (!std::filesystem::is_regular_file(path, ec))
        throw error(source_location{name}, "expected an OBJ file, found a device, pipe or socket; name a .obj file");
    if (!std::ifstream(path))
        throw error(source_location{name}, "expected a readable OBJ file, found one that cannot be opened; check its permissions");

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = path.has_parent_path() ? path.parent_path().string() : std::string(".");
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(name, config))
        throw error(source_location{name}, "expected a valid OBJ file, found: " + detail::one_line(reader.Error()));
    const std::string warning = detail::one_line(reader.Warning());
    if (warning.find("not found") != std::string::npos && warning.find("aterial") != std::string::npos)
        throw error(source_location{name},
                    "expected the material library it names, found: " + warning + "; put the .mtl file beside the .obj");

    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    obj_result result;
    mesh& m = result.geometry;
    m.source = name;

    const std::size_t vertex_count = attrib.vertices.size() / 3;
    const std::size_t normal_count = attrib.normals.size() / 3;
    const std::size_t texcoord_count = attrib.texcoords.size() / 2;
    std::size_t total_faces = 0;
    for (const tinyobj::shape_t& group : reader.GetShapes())
        total_faces += group.mesh.num_face_vertices.size();
    if (total_faces > limits.max_triangles)
        throw error(source_location{name}, "expected at most " + std::to_string(limits.max_triangles) +
                                               " triangles, found " + std::to_string(total_faces) +
                                               "; raise obj_limits::max_triangles");

    for (std::size_t i = 0; i < vertex_count; ++i) {
        const vec3 p(real(attrib.vertices[3 * i]), real(attrib.vertices[3 * i + 1]), real(attrib.vertices[3 * i + 2]));
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw error(source_location{name}, "expected finite vertex coordinates, found NaN or inf in vertex " +
                                                   std::to_string(i + 1) + "; fix the file");
        m.positions.push_back(p);
    }
    for (std::size_t i = 0; i < normal_count; ++i)
        m.normals.emplace_back(real(attrib.normals[3 * i]), real(attrib.normals[3 * i + 1]), real(attrib.normals[3 * i + 2]));
    for (std::size_t i = 0; i < texcoord_count; ++i)
        m.texcoords.emplace_back(real(attrib.texcoords[2 * i]), real(attrib.texcoords[2 * i + 1]));

    for (const tinyobj::material_t& source : reader.GetMaterials()) {
        material mat;
        mat.name = source.name;
        mat.ka = detail::to_color(source.ambient);
        mat.kd = detail::to_color(source.diffuse);
        mat.ks = detail::to_color(source.specular);
        mat.p = source.shininess > 0 ? real(source.shininess) : real(1);
        // MTL illumination models 3 and 5 are "reflection on": Ks is the mirror colour.
        mat.km = (source.illum == 3 || source.illum == 5) ? mat.ks : color(0.0f);
        result.materials.push_back(mat);
    }

    bool all_have_normals = normal_count > 0;
    bool all_have_texcoords = texcoord_count > 0;
    bool any_material = false;
    std::vector<int> face_materials;
    std::vector<index3> normal_indices, texcoord_indices;
    std::size_t face_number = 0;
    for (const tinyobj::shape_t& group : reader.GetShapes()) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < group.mesh.num_face_vertices.size(); ++f, ++face_number) {
            const std::size_t corners = group.mesh.num_face_vertices[f];
            if (corners != 3) {
                const source_location where{name, detail::obj_face_line(path, face_number)};
                throw parse_error(where, "a face of at least 3 vertices", "one of " + std::to_string(corners),
                                  "an OBJ face 'f' lists three or more vertex indices");
            }
            index3 position{}, normal{}, texcoord{};
            for (std::size_t k = 0; k < 3; ++k) {
                const tinyobj::index_t& index = group.mesh.indices[offset + k];
                if (index.vertex_index < 0 || std::size_t(index.vertex_index) >= vertex_count) {
                    const source_location where{name, detail::obj_face_line(path, face_number)};
                    throw parse_error(where, "a vertex index between 1 and " + std::to_string(vertex_count),
                                      "an index out of range", "OBJ indices count from 1 ('v' lines above the face)");
                }
                position[k] = std::uint32_t(index.vertex_index);
                if (index.normal_index < 0 || std::size_t(index.normal_index) >= normal_count)
                    all_have_normals = false;
                else
                    normal[k] = std::uint32_t(index.normal_index);
                if (index.texcoord_index < 0 || std::size_t(index.texcoord_index) >= texcoord_count)
                    all_have_texcoords = false;
                else
                    texcoord[k] = std::uint32_t(index.texcoord_index);
            }
            offset += corners;
            const vec3& a = m.positions[position[0]];
            const vec3& b = m.positions[position[1]];
            const vec3& c = m.positions[position[2]];
            const real twice_area = glm::length(glm::cross(b - a, c - a));
            if (!(twice_area > 0)) {
                ++m.dropped_degenerate;
                continue;
            }
            m.triangles.push_back(position);
            normal_indices.push_back(normal);
            texcoord_indices.push_back(texcoord);
            const int material_id = f < group.mesh.material_ids.size() ? group.mesh.material_ids[f] : -1;
            face_materials.push_back(material_id >= 0 && std::size_t(material_id) < result.materials.size() ? material_id : -1);
            any_material = any_material || face_materials.back() >= 0;
        }
    }
    if (all_have_normals)
        m.normal_indices = std::move(normal_indices);
    else
        m.normals.clear();
    if (all_have_texcoords)
        m.texcoord_indices = std::move(texcoord_indices);
    else
        m.texcoords.clear();
    if (any_material)
        m.face_materials = std::move(face_materials);
    return result;
}

} // namespace rt
