// shaded_stage.hpp - what the stage 05, 06, 07 and 09 programs share: read
// "SCENE [-o OUTPUT] [--pixel I J] [stage options]", render one centred
// sample per pixel with the stage's color function and the library's
// accelerator (stage::world, compiled once), and store it; or, with --pixel,
// tell that pixel's story (pixel_story.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <iostream>
#include <optional>
#include <string>

#include <rt/system/atomic_file.hpp>
#include <rt/camera/camera.hpp>
#include <rt/scene/scene.hpp>
#include <rt/shading/shading.hpp>

#include "light_terms.hpp"
#include "pixel_story.hpp"
#include "stage_main.hpp"
#include "support.hpp"

namespace stage {

/// What the pixel's story explains: shadow rays (stages 06 and 07) and
/// light falloff, as the stage's color function uses them.
struct story_options {
    bool shadows = false;
    bool falloff = false;
};

/// The command line of a program whose one option of its own is --max-depth N
/// (stages 07 and 09): SCENE [-o OUTPUT] [--max-depth N] [--pixel I J].
struct depth_command {
    std::string scene;
    std::string output;
    int max_depth = -1; ///< -1: the scene's own
    pixel_request pixel;

    /// What render_shaded's `adjust` does with it: --max-depth over the scene's.
    std::function<void(rt::scene&)> adjust() const
    {
        return [depth = max_depth](rt::scene& s) {
            if (depth >= 0)
                s.max_depth = depth;
        };
    }
};

/// That command line, `output` its default output; nullopt for --help (`usage` printed).
inline std::optional<depth_command> read_depth_command(arguments& args, const std::string& usage,
                                                       const std::string& output)
{
    depth_command c;
    c.output = output;
    const std::optional<std::string> scene_path = read_command_line(
        args, usage, "-o, --max-depth, --pixel, --pixel-json", [&](const std::string& arg) {
            if (arg == "--max-depth")
                c.max_depth = int(parse_integer(arg, args.value_of(arg), 0, 64));
            else
                return read_image_option(args, arg, c.output, c.pixel);
            return true;
        });
    if (!scene_path)
        return std::nullopt;
    c.scene = *scene_path;
    return c;
}

/// Renders `scene_path` with `color` to `output` (format from the extension),
/// or prints the story of `pixel`. `color(scene, accelerator, ray)` must take
/// any accelerator (a generic lambda): stage::world for the image, a
/// stage::recording of it for the story. `adjust` may change the loaded scene
/// first (a command-line override).
template <class Color>
void render_shaded(const std::string& program, const std::string& scene_path, const std::string& output,
                   const pixel_request& pixel, const story_options& explain, const Color& color,
                   const std::function<void(rt::scene&)>& adjust = {})
{
    if (!pixel.wanted) {
        check_image_output(output); // every option, the output format included, before any work
        check_input_and_outputs(scene_path, "a scene file", {file_argument(output)});
    }
    rt::scene s = stage::load_scene(scene_path);
    const std::uint64_t pixel_count = std::uint64_t(s.width) * std::uint64_t(s.height);
    if (!pixel.wanted) // the image (three floats a pixel) and its bytes
        check_after_load(scene_path, s, {file_argument(output)}, pixel_count * (12 + 3),
                         "a " + std::to_string(s.width) + "x" + std::to_string(s.height) + " image");
    if (adjust)
        adjust(s);
    const stage::world w(s);
    const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
    if (pixel.wanted) {
        story st;
        st.program = program;
        place_pixel(st, pixel.column, pixel.row, gen.nx, gen.ny);
        st.camera = rt::pixel_ray(gen, st.i, st.j);
        st.linear = color(s, recording<stage::world>(w, st.queries), st.camera);
        name_queries(st);
        explain_lights(st, s, explain.shadows, explain.falloff,
                       [](const rt::material& m, const rt::vec3& n, const rt::vec3& v, const rt::vec3& l,
                          const rt::color& I) { return rt::blinn_phong(m, n, v, l, I); });
        st.values.push_back({"stored bytes (clamped, gamma 2.2):", stored_bytes(st.linear, 2.2f)});
        if (pixel.json)
            print_story_json(std::cout, st, s);
        else
            print_story(std::cout, st, s);
        return;
    }
    const rt::image pixels = render_centres(
        s.width, s.height, [&gen](rt::real x, rt::real y) { return rt::generate_ray(gen, x, y); },
        [&](const rt::ray& r) { return color(s, w, r); });
    save_image(output, pixels, 2.2f);
    std::cerr << program << ": wrote " << output << " (" << s.width << "x" << s.height << ")\n";
}

} // namespace stage
