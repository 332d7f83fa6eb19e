// mesh.hpp - an indexed triangle mesh, as an OBJ file gives it (stage 04).
//
// A mesh stores only what its file provides: normals and texture coordinates
// are empty when the file has none. A triangle whose file face gave no normal
// (or texture coordinate) indices while others did has no_index there.
//
// Shading normals are interpolated across each triangle (Phong's normal
// interpolation, as in Physically Based Rendering, 3rd ed., sec. 3.6.2): at the
// hit with barycentrics (b0, b1, b2) the normal is
//     n = normalize(b0 na + b1 nb + b2 nc),
// turned to the side of the geometric normal that faces the ray.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "../core/hit_record.hpp"
#include "../core/vec.hpp"

namespace rt {

using index3 = std::array<std::uint32_t, 3>;

/// Marks a triangle corner without a normal or texture coordinate index.
constexpr std::uint32_t no_index = 0xffffffffu;

struct mesh {
    std::string source;                    ///< the path as the scene file wrote it
    /// the files the mesh was read from, as the OBJ loader opened them: the OBJ
    /// file, then each MTL file (empty for a mesh made in code); a program checks
    /// its outputs against them (rt::files_read, rt::check_not_input)
    std::vector<std::filesystem::path> read_from;
    std::vector<vec3> positions;
    std::vector<index3> triangles;         ///< position indices, one triple per triangle
    std::vector<vec3> normals;             ///< empty when the file has no normals
    std::vector<index3> normal_indices;    ///< parallel to triangles when normals exist
    std::vector<vec2> texcoords;           ///< empty when the file has no texture coordinates
    std::vector<index3> texcoord_indices;  ///< parallel to triangles when texcoords exist
    std::vector<int> face_materials;       ///< per triangle, from MTL; empty: all use `material`
    int material = -1;                     ///< index into scene::materials; -1: the default material
    std::size_t dropped_degenerate = 0;    ///< zero-area triangles left out when loading
};

/// The material of triangle i: its MTL material if the file gave one, else the mesh's.
inline int triangle_material(const mesh& m, std::size_t i)
{
    if (i < m.face_materials.size() && m.face_materials[i] >= 0)
        return m.face_materials[i];
    return m.material;
}

/// Completes a hit record that fill_triangle_record filled for triangle i of
/// `m`: the primitive index, the material, and the interpolated shading normal
/// when the mesh has normals for all three corners (else the geometric normal
/// stays). A shading normal that interpolates to zero keeps the geometric one.
inline void complete_mesh_hit(const mesh& m, std::size_t i, hit_record& rec)
{
    rec.primitive = std::uint32_t(i);
    rec.material = triangle_material(m, i);
    if (m.normals.empty() || i >= m.normal_indices.size())
        return;
    const index3& corner = m.normal_indices[i];
    if (corner[0] == no_index || corner[1] == no_index || corner[2] == no_index)
        return;
    const real b0 = 1 - rec.b1 - rec.b2;
    const vec3 n = b0 * m.normals[corner[0]] + rec.b1 * m.normals[corner[1]] + rec.b2 * m.normals[corner[2]];
    const real length = glm::length(n);
    if (!(length > 0) || !std::isfinite(length))
        return;
    const vec3 unit = n / length;
    rec.normal = glm::dot(unit, rec.geometric_normal) < 0 ? -unit : unit;
}

} // namespace rt
