// render_setup.hpp - what the render commands share between the command line and
// rt::render: load a scene file or frame a bare OBJ, choose what each sample
// computes (the shaded colour or a debug image), the camera's rays, and how the
// result is stored (stage 08).
//
// stage08_output and the interactive viewer (stages/viewer) both build their
// renders from these pieces, so the viewer shows, pixel for pixel, what
// stage08_output writes for the same camera and settings:
//
//     rt::scene s = rt::load_input("scenes/showcase.scene");
//     const rt::radiance_function radiance = rt::make_radiance(s, rt::aov_kind::none); // shaded
//     const rt::ray_source rays = rt::camera_rays(s.cam, s.width, s.height);
//     rt::render_result out = rt::render(options, rays, radiance);
//     rt::save_image("out.png", out.pixels, rt::output_encoding(rt::aov_kind::none, rt::encoding{}, out.pixels));
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

#include "accelerator.hpp"
#include "camera.hpp"
#include "encoding.hpp"
#include "error.hpp"
#include "hit_record.hpp"
#include "image.hpp"
#include "light.hpp"
#include "mesh.hpp"
#include "obj_loader.hpp"
#include "ray.hpp"
#include "ray_image.hpp"
#include "raytracer.hpp"
#include "renderer.hpp"
#include "sampler.hpp"
#include "scene.hpp"
#include "scene_loader.hpp"
#include "vec.hpp"
#include "watertight.hpp"

namespace rt {

/// What each sample computes: the shaded colour (none) or a debug image (an
/// "arbitrary output variable"): the hit's distance, its normal, its position,
/// or the camera ray's direction.
enum class aov_kind { none, depth, normal, position, rays };

inline std::optional<aov_kind> aov_from_name(const std::string& name)
{
    if (name == "depth")
        return aov_kind::depth;
    if (name == "normal")
        return aov_kind::normal;
    if (name == "position")
        return aov_kind::position;
    if (name == "rays")
        return aov_kind::rays;
    return std::nullopt;
}

/// "shaded" for aov_kind::none, otherwise the name aov_from_name reads.
inline const char* name_of(aov_kind kind)
{
    switch (kind) {
    case aov_kind::depth: return "depth";
    case aov_kind::normal: return "normal";
    case aov_kind::position: return "position";
    case aov_kind::rays: return "rays";
    case aov_kind::none: break;
    }
    return "shaded";
}

/// True when `path` ends in ".obj" (any case): a bare model, not a scene file.
inline bool has_obj_extension(const std::filesystem::path& path)
{
    std::string extension = path.extension().string();
    for (char& c : extension)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension == ".obj";
}

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
        throw error(source_location{path.string()}, "expected a model with at least one triangle, found none");
    const real pi = real(3.14159265358979323846);
    const vec3 centre = box.center();
    const real radius = std::max(glm::length(box.extent()) / 2, real(1e-6));
    const real fov = 40;
    // the bounding sphere fits the narrower of the two fields of view, with a 10% margin
    const real half =
        std::min(fov / 2 * pi / 180, std::atan(std::tan(fov / 2 * pi / 180) * real(s.width) / real(s.height)));
    const real distance = real(1.1) * radius / std::sin(half);
    s.cam.kind = projection::perspective;
    s.cam.look_at = centre;
    s.cam.eye = centre + distance * glm::normalize(vec3(0, real(0.3), 1));
    s.cam.up = vec3(0, 1, 0);
    s.cam.fov_degrees = fov;
    if (const std::optional<vec3> view = inside_view(std::get<mesh>(s.shapes.front()), centre)) {
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

/// The sampler used when none is named: one ray through each pixel centre for
/// 1 sample per pixel (the image of stages 02-07), jittered otherwise.
inline sampler_kind default_sampler(int samples_per_pixel)
{
    return samples_per_pixel == 1 ? sampler_kind::center : sampler_kind::jittered;
}

/// A ray source for rt::render: film position in pixels -> ray.
using ray_source = std::function<ray(real, real)>;
/// A radiance function for rt::render: the colour a ray brings back.
using radiance_function = std::function<color(const ray&, sample_context&)>;

/// The camera's rays for a full image of nx x ny pixels (camera.hpp).
inline ray_source camera_rays(const camera& cam, int nx, int ny)
{
    const ray_generator gen = make_ray_generator(cam, nx, ny);
    return [gen](real x, real y) { return generate_ray(gen, x, y); };
}

/// An accelerator seen through a counter of the queries made with it, so a
/// render reports its shadow and mirror rays as well as its camera rays. One
/// sample's own counter: it is made per sample, never shared between threads.
struct counting_accelerator {
    const accelerator* accel;
    std::uint64_t* queries;

    bool closest_hit(const ray& r, real tmin, real tmax, hit_record& rec) const
    {
        ++*queries;
        return accel->closest_hit(r, tmin, tmax, rec);
    }
    bool any_hit(const ray& r, real tmin, real tmax) const
    {
        ++*queries;
        return accel->any_hit(r, tmin, tmax);
    }
};

/// What each sample computes, for scene `s` whose accelerator (stage 04) is
/// `accel`: the shaded colour of stages 05-07 (rt::ray_color) or a debug image.
/// The function refers to `s` and `accel` (it shares ownership of `accel`;
/// `s` must outlive it) and neither may change while a render runs; between
/// renders, what it reads at each call (s.max_depth, lights, materials) may
/// change, while new shapes need a new accelerator.
inline radiance_function make_radiance(const scene& s, std::shared_ptr<const accelerator> accel, aov_kind aov)
{
    const real far = std::numeric_limits<real>::infinity();
    switch (aov) {
    case aov_kind::rays:
        return [](const ray& r, sample_context&) { return direction_to_color(r.direction); };
    case aov_kind::depth:
        // the distance along the ray, t |d|; 0 where the ray misses
        return [accel, far](const ray& r, sample_context&) {
            hit_record hit;
            return accel->closest_hit(r, 0, far, hit) ? color(float(hit.t * glm::length(r.direction))) : color(0.0f);
        };
    case aov_kind::normal:
        // the unit shading normal mapped to colour, (n + 1) / 2; black where the ray misses
        return [accel, far](const ray& r, sample_context&) {
            hit_record hit;
            return accel->closest_hit(r, 0, far, hit) ? color((hit.normal + vec3(1)) * real(0.5)) : color(0.0f);
        };
    case aov_kind::position:
        return [accel, far](const ray& r, sample_context&) {
            hit_record hit;
            return accel->closest_hit(r, 0, far, hit) ? color(hit.point) : color(0.0f);
        };
    case aov_kind::none: break;
    }
    const scene* shaded = &s;
    return [accel, shaded](const ray& r, sample_context& context) {
        std::uint64_t traced = 0;
        const color L = ray_color(*shaded, counting_accelerator{accel.get(), &traced}, r);
        context.rays += traced - 1; // the camera ray (the first query) is the renderer's own count
        return L;
    };
}

/// The same, building the accelerator of `s` (except for the rays image, which needs none).
inline radiance_function make_radiance(const scene& s, aov_kind aov)
{
    if (aov == aov_kind::rays)
        return make_radiance(s, nullptr, aov);
    // built once, shared by every worker thread (closest_hit and any_hit are const)
    return make_radiance(s, std::make_shared<const accelerator>(s), aov);
}

/// How `pixels`, an image of `aov`, is stored in 8 bits (PNG, PPM; PFM keeps
/// the floats as they are): the shaded image through `shaded`; an AOV is data,
/// not light, so it is stored without tone map or transfer curve (clamp, linear
/// bytes). Distances are not in [0, 1], so the depth image is scaled by the
/// image's own farthest hit: 0 (black) at the eye, 255 at the farthest point.
inline encoding output_encoding(aov_kind aov, const encoding& shaded, const image& pixels)
{
    if (aov == aov_kind::none)
        return shaded;
    encoding data{0.0f, tonemap_kind::clamp, transfer_kind::gamma, 1.0f};
    if (aov == aov_kind::depth) {
        float farthest = 0.0f;
        for (const color& c : pixels.pixels)
            if (std::isfinite(c.r))
                farthest = std::max(farthest, c.r);
        if (farthest > 0.0f)
            data.exposure = -std::log2(farthest); // scale by 2^exposure = 1 / farthest
    }
    return data;
}

/// `value` as the shortest text that the scene loader and the command-line
/// options (which read a double and round it to rt::real) turn back into
/// exactly `value`; the 17 digits of the double otherwise, which always come
/// back exactly.
inline std::string exact_number_text(real value)
{
    char buffer[64];
    auto read_back = [](const char* first, const char* last) {
        double parsed = 0;
        std::from_chars(first, last, parsed);
        return real(parsed);
    };
    const std::to_chars_result shortest = std::to_chars(buffer, buffer + sizeof buffer, value);
    if (shortest.ec == std::errc() && read_back(buffer, shortest.ptr) == value)
        return std::string(buffer, shortest.ptr);
    const std::to_chars_result full =
        std::to_chars(buffer, buffer + sizeof buffer, double(value), std::chars_format::general, 17);
    return std::string(buffer, full.ptr);
}

namespace detail {

inline std::string exact_vector_text(const vec3& v)
{
    return exact_number_text(v.x) + ' ' + exact_number_text(v.y) + ' ' + exact_number_text(v.z);
}

} // namespace detail

/// The camera as the arguments of a scene file's `camera` statement
/// (docs/scene-format.md), every number written so that it reads back exactly:
/// "perspective eye 0 1.6 6 look_at 0 0.7 0 up 0 1 0 fov 40 focal 1".
inline std::string camera_statement(const camera& cam)
{
    std::string text = cam.kind == projection::perspective ? "perspective" : "orthographic";
    text += " eye " + detail::exact_vector_text(cam.eye);
    text += " look_at " + detail::exact_vector_text(cam.look_at);
    text += " up " + detail::exact_vector_text(cam.up);
    if (cam.plane)
        text += " window " + exact_number_text(cam.plane->l) + ' ' + exact_number_text(cam.plane->r) +
                ' ' + exact_number_text(cam.plane->b) + ' ' + exact_number_text(cam.plane->t);
    else if (cam.fov_degrees)
        text += " fov " + exact_number_text(*cam.fov_degrees);
    text += " focal " + exact_number_text(cam.focal_distance);
    return text;
}

/// A camera from the arguments of a `camera` statement (what camera_statement
/// writes), checked as the scene loader checks it; `name` starts its messages.
/// Columns in messages count in `arguments`.
inline camera parse_camera_statement(const std::string& arguments, const std::string& name = "--camera")
{
    std::vector<token> tokens = detail::tokenize(arguments, source_location{name, 1});
    tokens.insert(tokens.begin(), token{"camera", 0});
    statement line(name, 1, std::move(tokens), int(arguments.size()) + 1);
    camera cam;
    parse_camera(line, cam);
    line.end();
    return cam;
}

} // namespace rt
