// scene_input.hpp - what the render commands accept as input: a scene file
// (scene_loader.hpp), or a bare OBJ model, framed by a camera and lit by a
// light at the eye (scene_from_obj).
//
//     rt::scene s = rt::load_input("model.obj");          // or "scenes/showcase.scene"
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <variant>

#include "../core/aabb.hpp"
#include "../core/error.hpp"
#include "../core/hit_record.hpp"
#include "../scene/light.hpp"
#include "../scene/mesh.hpp"
#include "../input/obj_loader.hpp"
#include "../system/path_text.hpp"
#include "../core/ray.hpp"
#include "../scene/scene.hpp"
#include "../input/scene_loader.hpp"
#include "../core/vec.hpp"
#include "../intersection/watertight.hpp"

namespace rt {

/// True when `path` ends in ".obj" (any case): a bare model, not a scene file.
inline bool has_obj_extension(const std::filesystem::path& path)
{
    std::string extension = detail::utf8_text(path.extension());
    for (char& c : extension)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension == ".obj";
}

namespace detail {

/// Where a bare model is seen from inside: the direction to look in from `p`
/// when `p` is enclosed by the model's inner faces, as in a room or a building
/// (the conference room, Sponza's atrium, open to the sky), or nothing for an
/// object to be seen from outside. Enclosed means: rays from p along the four
/// horizontal axes, straight down and along the four downward diagonals of a
/// cube all hit the model, and at most two of those nine nearest hits are on
/// the back of a face (walls face into the room; the sky above may be open).
/// A closed object wound outwards, such as the bunny, holds a point inside it
/// behind its back faces, and an open model (the Cornell box has no front
/// wall) lets a ray escape. The direction is the horizontal axis with the
/// farthest wall: the longest view. Brute force over the triangles: it runs
/// once per model.
inline std::optional<vec3> inside_view(const mesh& m, const vec3& p)
{
    const real k = real(0.57735026918962576); // 1 / sqrt(3)
    const vec3 directions[9] = {{1, 0, 0},   {-1, 0, 0}, {0, 0, 1},  {0, 0, -1}, {0, -1, 0},
                                {k, -k, k}, {k, -k, -k}, {-k, -k, k}, {-k, -k, -k}};
    int back_faces = 0;
    real longest = 0;
    vec3 view{0};
    for (int i = 0; i < 9; ++i) {
        const ray r{p, directions[i]};
        real nearest = std::numeric_limits<real>::infinity();
        bool front = false;
        for (const index3& corners : m.triangles) {
            const triangle tri{m.positions[std::size_t(corners[0])], m.positions[std::size_t(corners[1])],
                               m.positions[std::size_t(corners[2])], -1};
            hit_record rec;
            if (hit_triangle(tri, r, 0, nearest, rec)) {
                nearest = rec.t;
                front = rec.front_face;
            }
        }
        if (!std::isfinite(nearest))
            return std::nullopt; // a way out
        if (!front && ++back_faces > 2)
            return std::nullopt; // inside a closed object, or behind the walls
        if (i < 4 && nearest > longest) {
            longest = nearest;
            view = directions[i];
        }
    }
    return view;
}

} // namespace detail

/// A scene for a bare OBJ model: the model with its own materials (the
/// default material where it has none), a camera, and one light at that
/// camera's eye (the light stays there when the camera is moved later). The
/// camera frames the model's bounding sphere from the front and a little
/// above; a model that encloses the centre of its bounds (a room, a building:
/// inside_view) is seen from that centre instead, along its longest view.
inline scene scene_from_obj(const std::filesystem::path& path, int nx, int ny, const obj_limits& limits = {})
{
    obj_result obj = load_obj(path, limits);
    require_triangles(obj);
    scene s;
    s.width = nx;
    s.height = ny;
    s.materials = obj.materials;
    s.shapes.emplace_back(std::move(obj.geometry));
    const aabb box = bounds(std::get<mesh>(s.shapes.front())); // not scene_bounds: a stage-01 exercise
    if (box.empty())
        throw error(source_location{detail::utf8_text(path)}, "expected a model with at least one triangle, found none");
    const real pi = real(3.14159265358979323846);
    const vec3 centre = box.center();
    const real radius = std::max(glm::length(box.extent()) / 2, real(1e-6));
    const real fov = 40;
    // the bounding sphere fits the narrower of the two fields of view, with a margin of a tenth
    const real half =
        std::min(fov / 2 * pi / 180, std::atan(std::tan(fov / 2 * pi / 180) * real(s.width) / real(s.height)));
    const real distance = real(1.1) * radius / std::sin(half);
    s.cam.kind = projection::perspective;
    s.cam.look_at = centre;
    s.cam.eye = centre + distance * glm::normalize(vec3(0, real(0.3), 1));
    s.cam.up = vec3(0, 1, 0);
    s.cam.fov_degrees = fov;
    if (const std::optional<vec3> view = detail::inside_view(std::get<mesh>(s.shapes.front()), centre)) {
        s.cam.eye = centre;
        s.cam.look_at = centre + *view;
        s.cam.fov_degrees = real(70); // a room needs a wider view than an object
    }
    light lamp;
    lamp.kind = light_kind::point;
    lamp.position = s.cam.eye;
    lamp.intensity = color(1.0f);
    s.lights.push_back(lamp);
    return s;
}

/// A scene file, or a bare OBJ model framed by scene_from_obj. The size is
/// the scene's own (an OBJ: `width` x `height`, default 640 x 480); the caller
/// applies --width/--height to the render options.
inline scene load_input(const std::filesystem::path& path, std::optional<int> width = std::nullopt,
                        std::optional<int> height = std::nullopt, const load_options& options = {})
{
    if (has_obj_extension(path)) {
        const scene defaults;
        return scene_from_obj(path, width.value_or(defaults.width), height.value_or(defaults.height), options.obj);
    }
    return load_scene(path, options);
}

} // namespace rt
