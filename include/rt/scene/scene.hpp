// scene.hpp - everything a scene file declares, and nothing more.
//
// The course's scene representation is a flat list: shapes in the order the
// file declares them, with material and light collections beside them. Every
// setting has a default (docs/scene-format.md), so a file states only what it
// needs. Acceleration structures are built from a scene later (stage 04), never
// stored in it.
#pragma once

#include <cstddef>
#include <filesystem>
#include <variant>
#include <vector>

#include "../core/aabb.hpp"
#include "camera_model.hpp"
#include "light.hpp"
#include "material.hpp"
#include "mesh.hpp"
#include "sphere_shape.hpp"
#include "triangle_shape.hpp"
#include "../core/vec.hpp"

namespace rt {

/// One entry of the scene's flat list of shapes.
using shape = std::variant<sphere, triangle, mesh>;

struct scene {
    int width = 640;    ///< image width in pixels (nx)
    int height = 480;   ///< image height in pixels (ny)
    camera cam;
    lens_model lens;    ///< a thin lens (stage 10); aperture 0 is a pinhole
    std::vector<material> materials;
    std::vector<light> lights;
    std::vector<shape> shapes;
    color ambient{0.1f};     ///< Ia, the ambient light intensity
    color background{0.0f};  ///< the color of rays that hit nothing
    int samples = 1;         ///< samples per pixel
    int max_depth = 5;       ///< mirror recursion limit
    material default_material;  ///< used by shapes whose material index is -1

    const material& material_of(int index) const
    {
        return index < 0 ? default_material : materials[std::size_t(index)];
    }
};

inline aabb bounds(const sphere& s)
{
    aabb box;
    box.grow(s.center - vec3(s.radius));
    box.grow(s.center + vec3(s.radius));
    return box;
}

inline aabb bounds(const triangle& tri)
{
    aabb box;
    box.grow(tri.a);
    box.grow(tri.b);
    box.grow(tri.c);
    return box;
}

inline aabb bounds(const mesh& m)
{
    aabb box;
    for (const index3& face : m.triangles)
        for (std::uint32_t corner : face)
            box.grow(m.positions[corner]);
    return box;
}

/// The box around every shape of the scene (empty for a scene without shapes).
inline aabb scene_bounds(const scene& s)
{
    // RT_EXERCISE_BEGIN(stage01: scene bounds)
    aabb box;
    for (const shape& item : s.shapes)
        box.grow(std::visit([](const auto& concrete) { return bounds(concrete); }, item));
    return box;
    // RT_EXERCISE_END
}

/// Every file read to make `s`, loaded from `input` (a scene file or a bare
/// OBJ): `input` itself, then the OBJ and MTL files of each mesh as the loader
/// recorded them (mesh::read_from). A program checks each output against these
/// before it writes (rt::check_not_input), so that no output replaces an input.
inline std::vector<std::filesystem::path> files_read(const std::filesystem::path& input, const scene& s)
{
    std::vector<std::filesystem::path> files{input};
    for (const shape& item : s.shapes)
        if (const mesh* m = std::get_if<mesh>(&item))
            files.insert(files.end(), m->read_from.begin(), m->read_from.end());
    return files;
}

} // namespace rt
