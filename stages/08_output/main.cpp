// Stage 08 - the renderer command: a scene file or a bare OBJ in, an image out
// (tone map, gamma, store), with samplers, reconstruction filters, threads,
// crops and a progress bar. Options and examples: docs/renderer.md.
//
//     stage08_output scenes/showcase.scene -o render.png --spp 16
//     stage08_output ../shared/meshes/stanford-bunny.obj -o bunny.pfm --aov rays
//     stage08_output --pattern zoneplate --width 256 --height 256 --sampler jittered --spp 16 -o zp.png
//
// The shaded image needs stages 04-07 (scene intersection and shading), which
// are connected at the TODO(shading) hook of rt::make_radiance
// (include/rt/render_setup.hpp, shared with the viewer); until then the
// command renders the `rays` AOV and the analytic test patterns.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

#include <rt/camera.hpp>
#include <rt/encoding.hpp>
#include <rt/filter.hpp>
#include <rt/image_io.hpp>
#include <rt/progress.hpp>
#include <rt/render_setup.hpp>
#include <rt/renderer.hpp>
#include <rt/sampler.hpp>
#include <rt/scene.hpp>
#include <rt/tonemap.hpp>

#include "stage_main.hpp"

namespace {

const char* usage =
    "usage: stage08_output (SCENE | MODEL.obj | --pattern NAME) [options]\n"
    "Renders a scene file, a bare OBJ model (framed by a camera, lit from the camera),\n"
    "or an analytic test pattern, to an image whose format the extension names.\n"
    "  -o OUTPUT             .png or .ppm (8-bit, through the colour pipeline) or .pfm\n"
    "                        (linear floats, exact); default render.png\n"
    "  --width W, --height H image size in pixels (default: the scene's; 512x512 for a pattern)\n"
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
    "  --aov A               depth | normal | position | rays: a debug image instead of\n"
    "                        the shaded one, stored without exposure, tone map or gamma\n"
    "  --pattern P           zoneplate | edge: render an analytic test pattern, no scene\n"
    "  --crop X0 X1 Y0 Y1    render columns [X0, X1) and rows [Y0, Y1) (from the top-left)\n"
    "                        of the full image only; pieces paste together exactly\n"
    "  --quiet               no progress bar and no summary line\n"
    "  --help                this text\n";

std::string quoted(const std::string& text)
{
    return "'" + text + "'";
}

std::string number_text(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

/// A whole integer in [lo, hi], or a one-line error naming the option.
long long parse_integer(const std::string& option, const std::string& text, long long lo, long long hi)
{
    std::size_t used = 0;
    long long value = 0;
    try {
        value = std::stoll(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || value < lo || value > hi)
        throw rt::error("option " + option + ": expected an integer from " + std::to_string(lo) + " to " +
                        std::to_string(hi) + ", found " + quoted(text) + "; see --help");
    return value;
}

std::uint64_t parse_seed(const std::string& text)
{
    std::size_t used = 0;
    unsigned long long value = 0;
    try {
        if (!text.empty() && text[0] != '-')
            value = std::stoull(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size())
        throw rt::error("option --seed: expected an integer from 0 to 18446744073709551615, found " + quoted(text) +
                        "; see --help");
    return value;
}

/// A finite number in [lo, hi] (lo exclusive when `open_below`), or a one-line error.
double parse_number(const std::string& option, const std::string& text, double lo, double hi, bool open_below = false)
{
    std::size_t used = 0;
    double value = 0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    const bool low_ok = open_below ? value > lo : value >= lo;
    if (used == 0 || used != text.size() || !std::isfinite(value) || !low_ok || value > hi)
        throw rt::error("option " + option + ": expected a number in " + (open_below ? "(" : "[") +
                        number_text(lo) + ", " + number_text(hi) + "], found " + quoted(text) + "; see --help");
    return value;
}

template <class Kind>
Kind parse_name(const std::string& option, const std::string& text, std::optional<Kind> (*from_name)(const std::string&),
                const std::string& choices)
{
    const std::optional<Kind> kind = from_name(text);
    if (!kind)
        throw rt::error("option " + option + ": expected one of " + choices + ", found " + quoted(text) +
                        "; see --help");
    return *kind;
}

enum class pattern_kind { none, zoneplate, edge };

struct settings {
    std::string input, output = "render.png";
    std::optional<int> width, height, spp, max_depth;
    std::optional<rt::sampler_kind> sampler;
    rt::filter_kind filter = rt::filter_kind::box;
    std::optional<double> filter_radius;
    int threads = 0;
    rt::encoding encoding;
    std::uint64_t seed = 0;
    rt::aov_kind aov = rt::aov_kind::none;
    pattern_kind pattern = pattern_kind::none;
    std::optional<rt::crop_window> crop;
    std::optional<rt::camera> camera;
    bool quiet = false;
    bool help = false;
};

settings read_arguments(stage::arguments& args)
{
    settings s;
    while (!args.done()) {
        const std::string arg = args.take();
        auto value = [&] { return args.value_of(arg); };
        if (arg == "--help" || arg == "-h") {
            s.help = true;
        } else if (arg == "-o") {
            s.output = value();
        } else if (arg == "--width") {
            s.width = int(parse_integer(arg, value(), 1, 1 << 16));
        } else if (arg == "--height") {
            s.height = int(parse_integer(arg, value(), 1, 1 << 16));
        } else if (arg == "--spp") {
            s.spp = int(parse_integer(arg, value(), 1, 1 << 16));
        } else if (arg == "--sampler") {
            s.sampler = parse_name<rt::sampler_kind>(arg, value(), rt::sampler_from_name,
                                                     "center, grid, random, jittered, halton");
        } else if (arg == "--filter") {
            s.filter = parse_name<rt::filter_kind>(arg, value(), rt::filter_from_name, "box, tent, gaussian, mitchell");
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
                parse_name<rt::tonemap_kind>(arg, value(), rt::tonemap_from_name, "clamp, reinhard, aces");
        } else if (arg == "--exposure") {
            s.encoding.exposure = float(parse_number(arg, value(), -64, 64));
        } else if (arg == "--gamma") {
            s.encoding.transfer = rt::transfer_kind::gamma;
            s.encoding.gamma = float(parse_number(arg, value(), 0, 10, true));
        } else if (arg == "--seed") {
            s.seed = parse_seed(value());
        } else if (arg == "--aov") {
            s.aov = parse_name<rt::aov_kind>(arg, value(), rt::aov_from_name, "depth, normal, position, rays");
        } else if (arg == "--pattern") {
            const std::string name = value();
            if (name == "zoneplate")
                s.pattern = pattern_kind::zoneplate;
            else if (name == "edge")
                s.pattern = pattern_kind::edge;
            else
                throw rt::error("option --pattern: expected zoneplate or edge, found " + quoted(name) + "; see --help");
        } else if (arg == "--crop") {
            rt::crop_window c;
            c.x0 = int(parse_integer("--crop X0", args.value_of("--crop (4 numbers: X0 X1 Y0 Y1)"), 0, 1 << 16));
            c.x1 = int(parse_integer("--crop X1", args.value_of("--crop (4 numbers: X0 X1 Y0 Y1)"), 0, 1 << 16));
            c.y0 = int(parse_integer("--crop Y0", args.value_of("--crop (4 numbers: X0 X1 Y0 Y1)"), 0, 1 << 16));
            c.y1 = int(parse_integer("--crop Y1", args.value_of("--crop (4 numbers: X0 X1 Y0 Y1)"), 0, 1 << 16));
            s.crop = c;
        } else if (arg == "--quiet" || arg == "-q") {
            s.quiet = true;
        } else if (!arg.empty() && arg[0] == '-') {
            throw rt::error("expected an option (see --help), found " + quoted(arg));
        } else if (s.input.empty()) {
            s.input = arg;
        } else {
            throw rt::error("expected one scene or OBJ file, found also " + quoted(arg) + "; see --help");
        }
    }
    return s;
}

/// An analytic test pattern of the film position (x, y) in an nx x ny image.
rt::radiance_function make_pattern(pattern_kind pattern, int nx, int ny)
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
        settings set = read_arguments(args);
        if (set.help) {
            std::cout << usage;
            return 0;
        }
        if (set.input.empty() == (set.pattern == pattern_kind::none))
            throw rt::error(set.input.empty() ? "expected a scene file, an OBJ file or --pattern, found none; see --help"
                                              : "expected a scene file or --pattern, found both; see --help");
        if (set.pattern != pattern_kind::none && set.aov != rt::aov_kind::none)
            throw rt::error("expected --aov or --pattern, found both; a pattern has no scene to show");
        if (set.pattern != pattern_kind::none && set.camera)
            throw rt::error("expected --camera or --pattern, found both; a pattern has no camera");
        rt::check_image_output(set.output); // fail before the work, not after it

        rt::scene scene;
        if (set.pattern != pattern_kind::none)
            scene.width = scene.height = 512;
        else
            scene = rt::load_input(set.input, set.width, set.height);
        if (set.camera)
            scene.cam = *set.camera;

        rt::render_options options;
        options.width = set.width.value_or(scene.width);
        options.height = set.height.value_or(scene.height);
        options.samples_per_pixel = set.spp.value_or(scene.samples);
        options.sampler = set.sampler.value_or(rt::default_sampler(options.samples_per_pixel));
        options.reconstruction = rt::make_filter(
            set.filter, set.filter_radius ? std::optional<rt::real>(rt::real(*set.filter_radius)) : std::nullopt);
        options.threads = set.threads;
        options.seed = set.seed;
        options.crop = set.crop;
        scene.max_depth = set.max_depth.value_or(scene.max_depth);
        rt::check_render_options(options);

        rt::radiance_function radiance;
        rt::ray_source ray_at;
        if (set.pattern != pattern_kind::none) {
            radiance = make_pattern(set.pattern, options.width, options.height);
            ray_at = [](rt::real x, rt::real y) { return rt::ray{rt::vec3(x, y, 0), rt::vec3(0, 0, -1)}; };
        } else {
            radiance = rt::make_radiance(scene, set.aov);
            ray_at = rt::camera_rays(scene.cam, options.width, options.height);
        }

        rt::progress_bar bar(std::cerr, !set.quiet && rt::stderr_is_terminal());
        const rt::render_result result = rt::render(options, ray_at, radiance, bar.callback());
        bar.finish();

        rt::save_image(set.output, result.pixels, rt::output_encoding(set.aov, set.encoding));
        if (!set.quiet)
            std::cerr << "wrote " << set.output << ": " << rt::summary_line(result.stats) << " ("
                      << rt::name_of(options.sampler) << ", " << rt::name_of(options.reconstruction.kind) << " "
                      << options.reconstruction.radius << ")\n";
        return 0;
    });
}
