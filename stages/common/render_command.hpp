// render_command.hpp - what stage08_output is asked to do, read from its command
// line (the render options it shares with the viewer, render_arguments.hpp, and
// its own: -o, --pattern, --crop, --quiet, --pixel), the checks before the work,
// and the analytic test patterns it renders instead of a scene.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <rt/core/error.hpp>
#include <rt/output/aov.hpp>
#include <rt/output/image_io.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/rendering/scene_input.hpp>
#include <rt/system/atomic_file.hpp>
#include <rt/system/os_error.hpp>

#include "render_arguments.hpp"
#include "stage_main.hpp"

namespace stage {

enum class pattern_kind { none, zoneplate, edge };

/// What stage08_output was asked to do.
struct render_command {
    render_settings render;
    std::string output = "render.png";
    pattern_kind pattern = pattern_kind::none;
    std::optional<rt::crop_window> crop;
    bool quiet = false;
    pixel_request pixel;
};

/// stage08_output's command line; nullopt for --help (`usage` is printed).
inline std::optional<render_command> read_render_command(arguments& args, const std::string& usage)
{
    render_command s;
    const std::optional<std::string> input = read_command_line(
        args, usage, "-o, the render options, --pattern, --crop, --quiet, --pixel, --pixel-json",
        [&](const std::string& arg) {
            if (read_render_option(args, arg, s.render)) {
                // one of the options stage08_output shares with the viewer
            } else if (arg == "--pattern") {
                const std::string name = parse_choice(arg, args.value_of(arg), {"zoneplate", "edge"});
                s.pattern = name == "zoneplate" ? pattern_kind::zoneplate : pattern_kind::edge;
            } else if (arg == "--crop") {
                const std::string what = "--crop (4 numbers: X0 X1 Y0 Y1)";
                rt::crop_window c;
                c.x0 = int(parse_integer("--crop X0", args.value_of(what), 0, 1 << 16));
                c.x1 = int(parse_integer("--crop X1", args.value_of(what), 0, 1 << 16));
                c.y0 = int(parse_integer("--crop Y0", args.value_of(what), 0, 1 << 16));
                c.y1 = int(parse_integer("--crop Y1", args.value_of(what), 0, 1 << 16));
                s.crop = c;
            } else if (arg == "--quiet" || arg == "-q") {
                s.quiet = true;
            } else {
                return read_image_option(args, arg, s.output, s.pixel);
            }
            return true;
        },
        "a scene or OBJ file", true);
    if (!input)
        return std::nullopt;
    s.render.input = *input;
    return s;
}


/// The options that cannot go together, and the checks before any work: the
/// output can be written and the input read, and the output is not the input.
inline void check_render_command(const render_command& set)
{
    const render_settings& render = set.render;
    if (render.input.empty() == (set.pattern == pattern_kind::none))
        throw rt::error(render.input.empty() ? "expected a scene file, an OBJ file or --pattern, found none; see --help"
                                             : "expected a scene file or --pattern, found both; see --help");
    if (set.pattern != pattern_kind::none && render.aov != rt::aov_kind::shaded)
        throw rt::error("expected --aov or --pattern, found both; a pattern has no scene to show");
    if (set.pattern != pattern_kind::none && render.camera)
        throw rt::error("expected --camera or --pattern, found both; a pattern has no camera");
    if (set.pixel.wanted && set.pattern != pattern_kind::none)
        throw rt::error("expected --pixel or --pattern, found both; a pattern has no rays to tell of");
    if (set.pixel.wanted && render.aov != rt::aov_kind::shaded)
        throw rt::error("expected --pixel or --aov, found both; the story is the shaded image's");
    if (set.pixel.wanted)
        return;
    rt::check_image_output(file_argument(set.output)); // fail before the work, not after it
    if (set.pattern == pattern_kind::none)
        check_input_and_outputs(render.input,
                                rt::has_obj_extension(file_argument(render.input)) ? "an OBJ file" : "a scene file",
                                {file_argument(set.output)});
}

/// The image's memory fits the limit: three floats a pixel, then for 8 bits its
/// bytes, and for a PNG the filtered rows stb_image_write compresses (a lower bound).
inline void check_memory_for_image(const rt::render_options& options, const std::string& output)
{
    const rt::crop_window area = options.crop.value_or(rt::crop_window{0, options.width, 0, options.height});
    const std::string format = rt::image_format_of(file_argument(output));
    const std::uint64_t per_pixel = format == ".pfm" ? 12 : format == ".ppm" ? 15 : 18;
    rt::check_memory_for(std::uint64_t(area.x1 - area.x0) * std::uint64_t(area.y1 - area.y0) * per_pixel,
                         "a " + std::to_string(area.x1 - area.x0) + "x" + std::to_string(area.y1 - area.y0) + " image");
}

/// An analytic test pattern of the film position (x, y) in an nx x ny image.
inline std::function<rt::color(const rt::ray&, rt::sample_context&)> make_pattern(pattern_kind pattern, int nx, int ny)
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

} // namespace stage
