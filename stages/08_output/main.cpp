// Stage 08 - the renderer command: a scene file or a bare OBJ in, an image out
// (tone map, gamma, store), with samplers, reconstruction filters, threads,
// crops and a progress bar. Options and examples: docs/renderer.md.
//
//     stage08_output scenes/showcase.scene -o render.png --spp 16
//     stage08_output ../shared/meshes/stanford-bunny.obj -o bunny.pfm --aov rays
//     stage08_output --pattern zoneplate --width 256 --height 256 --sampler jittered --spp 16 -o zp.png
//
// Each sample's color is rt::ray_color (stages 05-07) over the scene's
// rt::accelerator (stage 04), or a debug image (--aov): rt::make_radiance in
// include/rt/rendering/radiance.hpp, shared with the viewer (stages/viewer). The
// renderer, the BVH and the stage-07 color are compiled once
// (stages/common/support_frame.cpp); this file holds stage 08's own part.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

#include <rt/output/aov.hpp>
#include <rt/camera/camera.hpp>
#include <rt/output/encoding_settings.hpp>
#include <rt/core/error.hpp>
#include <rt/output/image_io.hpp>
#include <rt/system/os_error.hpp>
#include <rt/rendering/progress.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/scene/scene.hpp>
#include <rt/rendering/scene_input.hpp>

#include "pixel_story.hpp"
#include "render_arguments.hpp"
#include "stage_main.hpp"
#include "support_frame.hpp"
#include "support.hpp"

namespace {

const std::string usage = std::string(
    "usage: stage08_output (SCENE | MODEL.obj | --pattern NAME) [options]\n"
    "Renders a scene file, a bare OBJ model (framed by a camera, lit from the camera),\n"
    "or an analytic test pattern, to an image whose format the extension names.\n"
    "  -o OUTPUT             .png or .ppm (8-bit, through the color pipeline) or .pfm\n"
    "                        (linear floats, exact); default render.png\n"
    ) + stage::render_options_usage +
    "  --pattern P           zoneplate | edge: render an analytic test pattern, no scene\n"
    "                        (512x512 unless --width and --height say otherwise)\n"
    "  --crop X0 X1 Y0 Y1    render columns [X0, X1) and rows [Y0, Y1) (from the top-left)\n"
    "                        of the full image only; pieces paste together exactly\n"
    "  --quiet               no progress bar and no summary line\n"
    "  --pixel I J           tell the story of one pixel instead of writing the image: the\n"
    "                        ray through its centre, every hit, light, shadow and mirror ray,\n"
    "                        the color and what exposure, tone map and encoding make of it;\n"
    "                        I is the column from the left, J the row from the top\n"
    "  --pixel-json I J      the same as JSON (infinities are null)\n"
    "  --help                this text\n";

enum class pattern_kind { none, zoneplate, edge };

struct settings {
    stage::render_settings render;
    std::string output = "render.png";
    pattern_kind pattern = pattern_kind::none;
    std::optional<rt::crop_window> crop;
    bool quiet = false;
    stage::pixel_request pixel;
};

/// The settings of the command line; nullopt for --help (the usage is printed).
std::optional<settings> read_arguments(stage::arguments& args)
{
    settings s;
    const std::optional<std::string> input = stage::read_command_line(
        args, usage, "-o, the render options, --pattern, --crop, --quiet, --pixel, --pixel-json",
        [&](const std::string& arg) {
            if (stage::read_render_option(args, arg, s.render)) {
                // one of the options stage08_output shares with the viewer
            } else if (arg == "--pattern") {
                const std::string name = stage::parse_choice(arg, args.value_of(arg), {"zoneplate", "edge"});
                s.pattern = name == "zoneplate" ? pattern_kind::zoneplate : pattern_kind::edge;
            } else if (arg == "--crop") {
                const std::string what = "--crop (4 numbers: X0 X1 Y0 Y1)";
                rt::crop_window c;
                c.x0 = int(stage::parse_integer("--crop X0", args.value_of(what), 0, 1 << 16));
                c.x1 = int(stage::parse_integer("--crop X1", args.value_of(what), 0, 1 << 16));
                c.y0 = int(stage::parse_integer("--crop Y0", args.value_of(what), 0, 1 << 16));
                c.y1 = int(stage::parse_integer("--crop Y1", args.value_of(what), 0, 1 << 16));
                s.crop = c;
            } else if (arg == "--quiet" || arg == "-q") {
                s.quiet = true;
            } else {
                return stage::read_image_option(args, arg, s.output, s.pixel);
            }
            return true;
        },
        "a scene or OBJ file", true);
    if (!input)
        return std::nullopt;
    s.render.input = *input;
    return s;
}

/// An analytic test pattern of the film position (x, y) in an nx x ny image.
std::function<rt::color(const rt::ray&, rt::sample_context&)> make_pattern(pattern_kind pattern, int nx, int ny)
{
    const double cx = nx / 2.0, cy = ny / 2.0;
    if (pattern == pattern_kind::zoneplate) {
        // L = (1 + cos(pi r^2 / w)) / 2, w = max(nx, ny): the local frequency
        // r / w cycles per pixel passes the Nyquist limit 1/2 at r = w / 2,
        // so every ring beyond that circle is aliasing
        const double w = std::max(nx, ny);
        return [=](const rt::ray& r, rt::sample_context&) {
            const double dx = double(r.origin.x) - cx, dy = double(r.origin.y) - cy;
            const double pi = 3.14159265358979323846;
            return rt::color(float(0.5 + 0.5 * std::cos(pi * (dx * dx + dy * dy) / w)));
        };
    }
    // a half-plane whose edge passes through the centre, 5 degrees from the vertical
    const double angle = 5 * 3.14159265358979323846 / 180;
    const double a = std::cos(angle), b = -std::sin(angle);
    return [=](const rt::ray& r, rt::sample_context&) {
        return rt::color(a * (double(r.origin.x) - cx) + b * (double(r.origin.y) - cy) < 0 ? 1.0f : 0.0f);
    };
}

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage08_output", [&] {
        stage::arguments args(argc, argv);
        const std::optional<settings> arguments = read_arguments(args);
        if (!arguments)
            return 0; // --help
        settings set = *arguments;
        const stage::render_settings& render = set.render;
        if (render.input.empty() == (set.pattern == pattern_kind::none))
            throw rt::error(render.input.empty()
                                ? "expected a scene file, an OBJ file or --pattern, found none; see --help"
                                : "expected a scene file or --pattern, found both; see --help");
        if (set.pattern != pattern_kind::none && render.aov != rt::aov_kind::shaded)
            throw rt::error("expected --aov or --pattern, found both; a pattern has no scene to show");
        if (set.pattern != pattern_kind::none && render.camera)
            throw rt::error("expected --camera or --pattern, found both; a pattern has no camera");
        if (set.pixel.wanted && set.pattern != pattern_kind::none)
            throw rt::error("expected --pixel or --pattern, found both; a pattern has no rays to tell of");
        if (set.pixel.wanted && render.aov != rt::aov_kind::shaded)
            throw rt::error("expected --pixel or --aov, found both; the story is the shaded image's");
        if (!set.pixel.wanted) {
            rt::check_image_output(stage::file_argument(set.output)); // fail before the work, not after it
            if (set.pattern == pattern_kind::none)
                stage::check_input_and_outputs(
                    render.input,
                    rt::has_obj_extension(stage::file_argument(render.input)) ? "an OBJ file" : "a scene file",
                    {stage::file_argument(set.output)});
        }

        rt::scene scene;
        if (set.pattern != pattern_kind::none)
            scene.width = scene.height = 512;
        else
            scene = stage::load_render_input(render); // with --camera and --max-depth applied
        if (set.pattern == pattern_kind::none)
            rt::check_not_input(stage::file_argument(set.output),
                               rt::files_read(stage::file_argument(render.input), scene)); // its OBJ and MTL files too

        rt::render_options options = stage::render_options_for(render, scene);
        options.crop = set.crop;
        rt::check_render_options(options);
        {
            // the image (three floats a pixel), then for 8 bits its bytes, and for
            // a PNG the filtered rows stb_image_write compresses: a lower bound
            const rt::crop_window area = options.crop.value_or(rt::crop_window{0, options.width, 0, options.height});
            const std::string format = rt::image_format_of(stage::file_argument(set.output));
            const std::uint64_t per_pixel = format == ".pfm" ? 12 : format == ".ppm" ? 15 : 18;
            rt::check_memory_for(std::uint64_t(area.x1 - area.x0) * std::uint64_t(area.y1 - area.y0) * per_pixel,
                                 "a " + std::to_string(area.x1 - area.x0) + "x" + std::to_string(area.y1 - area.y0) +
                                     " image");
        }

        if (set.pixel.wanted) {
            // the ray through the pixel's centre, traced by the stage-07 color function
            stage::story st =
                stage::shaded_story(scene, "stage08_output", set.pixel.column, set.pixel.row, options.width, options.height);
            stage::add_encoding_story(st, render.encoding, options.samples_per_pixel);
            if (set.pixel.json)
                stage::print_story_json(std::cout, st, scene);
            else
                stage::print_story(std::cout, st, scene);
            return 0;
        }

        // the renderer, the BVH and the stage-07 color are compiled once
        // (support_frame.cpp): an edit to a stage-08 exercise rebuilds none of them
        rt::progress_bar bar(std::cerr, !set.quiet && rt::detail::stderr_is_terminal());
        const rt::render_result result =
            set.pattern != pattern_kind::none
                ? stage::render_image(
                      options, [](rt::real x, rt::real y) { return rt::ray{rt::vec3(x, y, 0), rt::vec3(0, 0, -1)}; },
                      make_pattern(set.pattern, options.width, options.height), bar.callback())
                : stage::render_scene(scene, render.aov, options, bar.callback());
        bar.finish();

        stage::save_encoded(set.output, result.pixels, render.aov, render.encoding);
        if (!set.quiet) {
            std::cerr << "wrote " << set.output << ": " << rt::summary_line(result.stats) << " ("
                      << rt::name_of(options.sampler) << ", " << rt::name_of(options.reconstruction.kind) << " "
                      << options.reconstruction.radius << ")";
            if (set.pattern == pattern_kind::none && render.aov != rt::aov_kind::rays) // the BVH traced it
                std::cerr << ", BVH " << stage::simd_path();
            std::cerr << "\n";
        }
        return 0;
    });
}
