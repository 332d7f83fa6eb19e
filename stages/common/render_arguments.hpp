// render_arguments.hpp - the render options that stage08_output and the viewer
// share (--width ... --aov, --camera), read with the same checks and the same
// one-line messages, and turned into rt::render_options the same way.
#pragma once

#include <cmath>
#include <cstdint>
#include <exception>
#include <optional>
#include <sstream>
#include <string>

#include <rt/camera/camera.hpp>
#include <rt/output/encoding_settings.hpp>
#include <rt/core/error.hpp>
#include <rt/rendering/filter.hpp>
#include <rt/output/aov.hpp>
#include <rt/input/camera_statement.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/rendering/sampler.hpp>
#include <rt/scene/scene.hpp>

#include "stage_main.hpp"
#include "support.hpp"

namespace stage {

/// The help lines of the shared options.
inline constexpr const char* render_options_usage =
    "  --width W, --height H image size in pixels (default: the scene's)\n"
    "  --spp N               samples per pixel, 1..65536 (default: the scene's `samples`)\n"
    "  --sampler S           center | grid | random | jittered | halton\n"
    "                        (default: center for 1 spp, jittered otherwise)\n"
    "  --filter F            box | tent | gaussian | mitchell (default box)\n"
    "  --filter-radius R     the filter's radius in pixels, (0, 16] (default: the filter's own)\n"
    "  --threads N           worker threads, 0 = all cores (default 0)\n"
    "  --camera \"ARGS\"       the camera instead of the scene's, as the arguments of a scene\n"
    "                        file's camera statement: \"perspective eye X Y Z look_at X Y Z\n"
    "                        up X Y Z fov DEGREES\" (the viewer prints them)\n"
    "  --max-depth N         mirror recursion limit, 0..64 (default: the scene's max_depth)\n"
    "  --tonemap T           clamp | reinhard | aces (default clamp)\n"
    "  --exposure STOPS      scale the image by 2^STOPS before the tone map (default 0)\n"
    "  --gamma G             store with a plain gamma G instead of the sRGB curve\n"
    "  --seed N              seed of every random choice, 0..2^64-1 (default 0)\n"
    "  --strict              warnings of the OBJ files (missing materials) are errors\n"
    "  --aov A               depth | normal | position | rays: a debug image instead of\n"
    "                        the shaded one, stored without exposure, tone map or gamma\n";

/// Everything the shared options set; unset optionals mean "the scene's".
struct render_settings {
    std::string input;  ///< the scene file or OBJ model
    std::optional<int> width, height, spp, max_depth;
    std::optional<rt::sampler_kind> sampler;
    rt::filter_kind filter = rt::filter_kind::box;
    std::optional<double> filter_radius;
    int threads = 0;
    rt::encoding encoding;
    std::uint64_t seed = 0;
    rt::aov_kind aov = rt::aov_kind::shaded;
    std::optional<rt::camera> camera;
    bool strict = false; ///< --strict: warnings of OBJ files are errors
};

/// If `arg` (just taken from `args`) is a shared option, reads its value into
/// `s` and returns true; otherwise returns false and reads nothing.
inline bool read_render_option(arguments& args, const std::string& arg, render_settings& s)
{
    auto value = [&] { return args.value_of(arg); };
    if (arg == "--width") {
        s.width = int(parse_integer(arg, value(), 1, 1 << 16));
    } else if (arg == "--height") {
        s.height = int(parse_integer(arg, value(), 1, 1 << 16));
    } else if (arg == "--spp") {
        s.spp = int(parse_integer(arg, value(), 1, 1 << 16));
    } else if (arg == "--sampler") {
        s.sampler = parse_name<rt::sampler_kind>(arg, value(), rt::sampler_from_name,
                                                 rt::detail::names_listed(rt::sampler_names));
    } else if (arg == "--filter") {
        s.filter = parse_name<rt::filter_kind>(arg, value(), rt::filter_from_name, rt::detail::names_listed(rt::filter_names));
    } else if (arg == "--filter-radius") {
        s.filter_radius = parse_number(arg, value(), 0, 16, true);
    } else if (arg == "--threads") {
        s.threads = int(parse_integer(arg, value(), 0, 1024));
    } else if (arg == "--camera") {
        s.camera = rt::parse_camera_statement(value(), "--camera");
    } else if (arg == "--max-depth") {
        s.max_depth = int(parse_integer(arg, value(), 0, 64));
    } else if (arg == "--tonemap") {
        s.encoding.tonemap =
            parse_name<rt::tonemap_kind>(arg, value(), rt::tonemap_from_name, rt::detail::names_listed(rt::tonemap_names));
    } else if (arg == "--exposure") {
        s.encoding.exposure = float(parse_number(arg, value(), -64, 64));
    } else if (arg == "--gamma") {
        s.encoding.transfer = rt::transfer_kind::gamma;
        s.encoding.gamma = float(parse_number(arg, value(), 0, 10, true));
    } else if (arg == "--seed") {
        s.seed = parse_seed(arg, value());
    } else if (arg == "--strict") {
        s.strict = true;
    } else if (arg == "--aov") {
        s.aov = parse_name<rt::aov_kind>(arg, value(), rt::aov_from_name, "depth, normal, position, rays");
    } else {
        return false;
    }
    return true;
}

/// The scene or OBJ of the settings, with --camera applied.
inline rt::scene load_render_input(const render_settings& s)
{
    // stage::load_input: the loaders are compiled once (support_input.cpp)
    rt::scene scene = stage::load_input(s.input, s.width, s.height, s.strict);
    if (s.camera)
        scene.cam = *s.camera;
    if (s.max_depth)
        scene.max_depth = *s.max_depth;
    return scene;
}

/// The render options of the settings for `scene` (its size and samples unless overridden).
inline rt::render_options render_options_for(const render_settings& s, const rt::scene& scene)
{
    rt::render_options options;
    options.width = s.width.value_or(scene.width);
    options.height = s.height.value_or(scene.height);
    options.samples_per_pixel = s.spp.value_or(scene.samples);
    options.sampler = s.sampler.value_or(rt::default_sampler(options.samples_per_pixel));
    options.reconstruction =
        rt::make_filter(s.filter, s.filter_radius ? std::optional<rt::real>(rt::real(*s.filter_radius)) : std::nullopt);
    options.threads = s.threads;
    options.seed = s.seed;
    return options;
}

} // namespace stage
