// mesh.hpp - an indexed triangle mesh, as an OBJ file gives it (stage 04).
//
// A mesh stores only what its file provides: normals and texture coordinates
// are empty when the file has none.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "vec.hpp"

namespace rt {

using index3 = std::array<std::uint32_t, 3>;

struct mesh {
    std::string source;                    ///< the path as the scene file wrote it
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

} // namespace rt
