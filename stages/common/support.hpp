// support.hpp - the heavy parts of the stage programs that a student's edit
// rarely touches (reading a scene file or an OBJ model, writing an image, the
// library's BVH, the threaded renderer), compiled once into small libraries
// (stages/CMakeLists.txt) rather than in every program. An edit to an exercise
// header then rebuilds only the stage's own main.cpp and test suite: seconds,
// not a minute.
//
//     const rt::scene s = stage::load_scene("scenes/showcase.scene");
//     const stage::world w(s);                        // rt::accelerator: BVH, robust tests
//     rt::hit_record hit;
//     if (w.closest_hit(r, 0, rt::infinity, hit)) ...
//     const rt::image img = stage::render_centres(s.width, s.height, rays, color);
//     stage::save_image("out.png", img, 2.2f);
//
// Each function is the library's own (rt::load_scene, rt::load_input,
// rt::accelerator, rt::render, rt::save_image); only where it is compiled differs.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <rt/core/hit_record.hpp>
#include <rt/core/image.hpp>
#include <rt/core/ray.hpp>
#include <rt/scene/scene.hpp>
#include <rt/core/vec.hpp>

#include <rt/bvh/accelerator_fwd.hpp> // rt::accelerator named, not defined: this header stays light

namespace stage {

/// rt::load_scene: the scene file at `path`, or an rt::error naming file:line:col.
/// `strict`: the OBJ files' warnings (missing materials, polygons that are not
/// simple) are errors (--strict).
rt::scene load_scene(const std::string& path, bool strict = false);

/// rt::load_input: a scene file, or a bare OBJ model framed by its bounds
/// (`width` x `height` pixels, default 640 x 480).
rt::scene load_input(const std::string& path, std::optional<int> width = std::nullopt,
                     std::optional<int> height = std::nullopt, bool strict = false);

/// rt::save_image: `img` to `path` (.png, .ppm or .pfm), written atomically;
/// 8-bit formats clamp and apply 1/gamma (1: bytes proportional to the values).
void save_image(const std::string& path, const rt::image& img, float gamma = 2.2f);

/// How many shapes of each kind a scene holds, and the triangles of its meshes.
struct shape_counts {
    std::size_t spheres = 0, triangles = 0, meshes = 0, mesh_triangles = 0;
};

inline shape_counts count_shapes(const rt::scene& s)
{
    shape_counts n;
    for (const rt::shape& item : s.shapes) {
        if (std::holds_alternative<rt::sphere>(item))
            ++n.spheres;
        else if (std::holds_alternative<rt::triangle>(item))
            ++n.triangles;
        else {
            ++n.meshes;
            n.mesh_triangles += std::get<rt::mesh>(item).triangles.size();
        }
    }
    return n;
}

/// One image to write: where, what, and the gamma of 8-bit formats.
struct image_output {
    std::string path;
    const rt::image* pixels;
    float gamma = 2.2f;
};

/// Writes every image or none (rt::write_all_atomically): each file is
/// complete before the first replaces its target.
void save_images(const std::vector<image_output>& outputs);

/// rt::check_image_output: an rt::error unless `path` names a writable
/// .png, .ppm or .pfm file (call it before any work).
void check_image_output(const std::string& path);

/// The three bytes save_image stores for a linear color `c` ("186 137 0").
std::string stored_bytes(const rt::color& c, float gamma = 2.2f);

/// The library's scene-level intersection (rt::accelerator: the BVH, the
/// watertight triangle test, the stable sphere method) for scene `s`, which
/// must outlive it. Its closest_hit and any_hit are rt::accelerator's, so it
/// can be passed wherever an accelerator is expected (rt::light_visible,
/// rt::ray_color). `kind` is "flat", "bvh" or "auto".
class world {
public:
    explicit world(const rt::scene& s, const std::string& kind = "auto");
    ~world();
    world(const world&) = delete;
    world& operator=(const world&) = delete;

    bool closest_hit(const rt::ray& r, rt::real tmin, rt::real tmax, rt::hit_record& rec) const;
    bool any_hit(const rt::ray& r, rt::real tmin, rt::real tmax) const;

    /// The accelerator itself, shared (rt::make_radiance takes it: a program
    /// that renders through the world never compiles the BVH's build).
    std::shared_ptr<const rt::accelerator> shared() const { return impl_; }

    /// "flat" or "bvh": what "auto" chose.
    std::string kind() const;
    /// How many primitives it holds (a mesh's triangles each count) and, for a BVH, its nodes.
    std::size_t primitives() const;
    std::size_t nodes() const;

private:
    std::shared_ptr<const rt::accelerator> impl_;
};

/// The BVH's fast path the world's accelerator takes on this CPU, as
/// support_world.cpp is compiled: "avx512 (8-wide)", "avx2 (8-wide)", "sse
/// (4-wide)" or "scalar (4-wide)" (rt::accelerator::automatic_path; x86-64
/// builds without -mavx2 pick one of the first three at run time,
/// rt/bvh/dispatch.hpp).
std::string simd_path();

/// A ray through a film position (pixels from the bottom-left corner).
using ray_source = std::function<rt::ray(rt::real, rt::real)>;
/// The color a ray brings back.
using color_function = std::function<rt::color(const rt::ray&)>;

/// An nx x ny image, one ray through each pixel centre (the image of stages
/// 02-07), traced on every core by rt::render; the top row is stored first.
rt::image render_centres(int nx, int ny, const ray_source& rays, const color_function& color);

} // namespace stage
