// Stage 11 - path tracing: light that bounces, from surfaces that glow
// (include/rt/path_tracing/hemisphere.hpp, lambertian.hpp, next_event.hpp, mis.hpp,
// roulette.hpp, adaptive.hpp; joined by path_tracer.hpp).
//
//     stage11_path_tracing scenes/cornell.scene -o cornell.png [--spp N] [--strategy mis] [--adaptive]
//     stage11_path_tracing ../shared/meshes/CornellBox-Original.obj -o cornell.png
//
// Every surface is Lambertian (its kd), the glowing triangles (emission, an
// MTL file's Ke) are the lights, and the background is the light of a uniform
// environment; the scene's point lights are stage 05's and play no part here.
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include <rt/bvh/accelerator.hpp>
#include <rt/system/atomic_file.hpp>
#include <rt/path_tracing/emitters.hpp>
#include <rt/core/enum_names.hpp>
#include <rt/path_tracing/mis.hpp>
#include <rt/path_tracing/path_tracer.hpp>
#include <rt/rendering/radiance.hpp> // camera_rays
#include <rt/scene/scene.hpp>
#include <rt/rendering/scene_input.hpp> // has_obj_extension

#include "stage_main.hpp"
#include "support.hpp"

namespace {

/// A point, direction or color (rt::vec3 or rt::color, float or double) as "(x, y, z)".
template <class T>
std::string text(const glm::vec<3, T, glm::defaultp>& v)
{
    std::ostringstream out;
    out << std::setprecision(6) << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return out.str();
}

/// A path's story, bounce by bounce, in words.
void print_story(std::ostream& out, const rt::path_story& st, const rt::scene& s, const rt::ray& camera, int column,
                 int row, const rt::path_options& o)
{
    out << "pixel (" << column << ", " << row << "): the render's first sample, strategy " << rt::name_of(o.strategy)
        << (o.roulette ? ", Russian roulette from bounce " + std::to_string(o.roulette_start) : ", no roulette") << "\n";
    out << "  camera ray from " << text(camera.origin) << " along " << text(camera.direction) << "\n";
    int bounce = 0;
    for (const rt::path_vertex& v : st.vertices) {
        const rt::material& m = s.material_of(v.material);
        out << "  bounce " << bounce << ": hit " << text(v.point) << ", material '" << m.name << "' (kd "
            << text(m.kd) << "), throughput " << text(v.throughput) << "\n";
        if (v.emitted != rt::color(0.0f))
            out << "    it glows: Le " << text(v.emitted) << ", weight " << v.emitted_weight
                << (v.emitted_weight == 0 ? " (next-event estimation counted it already)" : "") << "\n";
        if (v.light_sampled) {
            out << "    next-event estimation: the light point " << text(v.light_point);
            if (v.light_estimate == rt::color(0.0f) && m.kd == rt::color(0.0f))
                out << ": the surface reflects nothing (kd 0)\n";
            else if (v.light_estimate == rt::color(0.0f))
                out << " is below the surface, or the surface is behind the light: nothing\n";
            else if (!v.light_visible)
                out << " is hidden: the shadow ray is blocked\n";
            else
                out << " is visible: estimate " << text(v.light_estimate) << ", weight " << v.light_weight << "\n";
        }
        out << "    adds " << text(v.added) << "\n";
        if (v.bounced)
            out << "    next direction " << text(v.direction) << ", pdf " << v.pdf << ", weight f cos / pdf "
                << text(v.weight) << "\n";
        if (v.roulette_played)
            out << "    Russian roulette: " << (v.survived ? "goes on" : "ends here") << "\n";
        ++bounce;
    }
    if (st.escaped)
        out << "  the path leaves the scene: background " << text(s.background) << " adds " << text(st.background_added)
            << "\n";
    out << "  " << st.ending << "\n";
    out << "  radiance of this sample: " << text(st.radiance) << "\n";
}

void print_story_json(std::ostream& out, const rt::path_story& st, const rt::scene& s, int column, int row)
{
    auto v3 = [](const rt::vec3& v) {
        std::ostringstream o;
        o << std::setprecision(9) << "[" << v.x << ", " << v.y << ", " << v.z << "]";
        return o.str();
    };
    auto c3 = [&](const rt::color& c) { return v3(rt::vec3(rt::real(c.r), rt::real(c.g), rt::real(c.b))); };
    out << "{\"pixel\": [" << column << ", " << row << "], \"bounces\": [";
    for (std::size_t i = 0; i < st.vertices.size(); ++i) {
        const rt::path_vertex& v = st.vertices[i];
        out << (i ? ", " : "") << "{\"point\": " << v3(v.point) << ", \"material\": \""
            << rt::detail::printable(s.material_of(v.material).name) << "\", \"throughput\": " << c3(v.throughput)
            << ", \"emitted\": " << c3(v.emitted) << ", \"emitted_weight\": " << v.emitted_weight
            << ", \"light_visible\": " << (v.light_visible ? "true" : "false") << ", \"light_estimate\": "
            << c3(v.light_estimate) << ", \"light_weight\": " << v.light_weight << ", \"added\": " << c3(v.added)
            << ", \"direction\": " << v3(v.direction) << ", \"pdf\": " << v.pdf << ", \"survived\": "
            << (v.survived ? "true" : "false") << "}";
    }
    out << "], \"escaped\": " << (st.escaped ? "true" : "false") << ", \"radiance\": " << c3(st.radiance) << "}\n";
}

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage11_path_tracing", [&] {
        stage::arguments args(argc, argv);
        std::string output = "path.png";
        int spp = 0;
        std::uint64_t seed = 0;
        rt::path_render_options options;
        stage::pixel_request pixel;
        const std::string usage =
            std::string("usage: stage11_path_tracing SCENE [-o OUTPUT] [--spp N] [--seed S] [--strategy S]\n"
                        "                            [--adaptive] [--tolerance T] [--batch B] [--no-roulette]\n"
                        "Renders SCENE (a scene file or an OBJ model) by path tracing: Lambertian surfaces lit by\n"
                        "the triangles that glow (emission, Ke) and by the background.\n"
                        "  -o OUTPUT      .png, .ppm or .pfm (default path.png)\n"
                        "  --spp N        samples per pixel, 1..65536 (default: the scene's samples); with\n"
                        "                 --adaptive the most a pixel takes\n"
                        "  --seed S       the random numbers' seed (default 0)\n"
                        "  --strategy S   uniform, cosine (BSDF sampling only), nee (next-event estimation)\n"
                        "                 or mis (both, by the power heuristic; the default)\n"
                        "  --adaptive     stop a pixel when 1.96 sigma / sqrt(n) <= tolerance * mean\n"
                        "  --tolerance T  adaptive sampling's relative tolerance (default 0.05)\n"
                        "  --batch B      adaptive sampling's samples between two tests (default 32)\n"
                        "  --no-roulette  no Russian roulette: paths end after --max-bounces\n"
                        "  --max-bounces N  the most bounces of a path, 0..10000 (default 64)\n") +
            stage::pixel_help;
        const std::optional<std::string> scene_path = stage::read_command_line(
            args, usage,
            "-o, --spp, --seed, --strategy, --adaptive, --tolerance, --batch, --no-roulette, --max-bounces, --pixel, "
            "--pixel-json",
            [&](const std::string& arg) {
                if (arg == "--spp")
                    spp = int(stage::parse_integer(arg, args.value_of(arg), 1, 1 << 16));
                else if (arg == "--seed")
                    seed = std::uint64_t(stage::parse_integer(arg, args.value_of(arg), 0, 1LL << 62));
                else if (arg == "--strategy")
                    options.path.strategy = stage::parse_name<rt::path_strategy>(
                        arg, args.value_of(arg),
                        [](const std::string& w) { return rt::detail::value_named(rt::path_strategy_names, w); },
                        rt::detail::names_listed(rt::path_strategy_names));
                else if (arg == "--adaptive")
                    options.adaptive = true;
                else if (arg == "--tolerance")
                    options.max_tolerance = stage::parse_number(arg, args.value_of(arg), 0, 1, true);
                else if (arg == "--batch")
                    options.batch = int(stage::parse_integer(arg, args.value_of(arg), 2, 1 << 16));
                else if (arg == "--no-roulette")
                    options.path.roulette = false;
                else if (arg == "--max-bounces")
                    options.path.max_bounces = int(stage::parse_integer(arg, args.value_of(arg), 0, 10000));
                else
                    return stage::read_image_option(args, arg, output, pixel);
                return true;
            });
        if (!scene_path)
            return 0; // --help
        if (!pixel.wanted) {
            stage::check_image_output(output);
            stage::check_input_and_outputs(
                *scene_path, rt::has_obj_extension(stage::file_argument(*scene_path)) ? "an OBJ file" : "a scene file",
                {stage::file_argument(output)});
        }
        const rt::scene s = stage::load_input(*scene_path);
        const rt::accelerator accel(s);
        const rt::emitter_list lights = rt::find_emitters(s);
        const rt::ray_source rays = rt::camera_rays(s.cam, s.width, s.height);
        if (pixel.wanted) {
            if (pixel.column >= s.width || pixel.row >= s.height)
                throw rt::error("option --pixel: expected a pixel of the " + std::to_string(s.width) + "x" +
                                std::to_string(s.height) + " image, found (" + std::to_string(pixel.column) + ", " +
                                std::to_string(pixel.row) + ")");
            // the render's first sample of the pixel: the same generator, the same numbers
            const std::uint64_t index = std::uint64_t(pixel.row) * std::uint64_t(s.width) + std::uint64_t(pixel.column);
            rt::pcg32 rng = rt::seeded_generator(seed, index, 1, rt::integrator_stream);
            const rt::real fx = rng.next_float(), fy = rng.next_float();
            const rt::ray camera = rays(rt::real(pixel.column) + fx, rt::real(s.height - 1 - pixel.row) + fy);
            rt::path_story story;
            (void)rt::path_radiance(s, accel, lights, camera, rng, options.path, rt::path_story_recorder{&story});
            if (pixel.json)
                print_story_json(std::cout, story, s, pixel.column, pixel.row);
            else
                print_story(std::cout, story, s, camera, pixel.column, pixel.row, options.path);
            return 0;
        }
        rt::check_not_input(stage::file_argument(output), rt::files_read(stage::file_argument(*scene_path), s));
        options.width = s.width;
        options.height = s.height;
        options.samples_per_pixel = spp > 0 ? spp : s.samples;
        options.seed = seed;
        const rt::path_render_result out = rt::render_paths(s, accel, lights, rays, options);
        stage::save_image(output, out.pixels, 2.2f);
        double mean_samples = 0;
        for (const int n : out.samples)
            mean_samples += double(n) / double(out.samples.size());
        std::cerr << "stage11_path_tracing: wrote " << output << " (" << s.width << "x" << s.height << ", "
                  << rt::name_of(options.path.strategy) << ", " << std::setprecision(4) << mean_samples
                  << " samples per pixel on average, " << lights.triangles.size() << " glowing triangles, "
                  << std::setprecision(3) << out.seconds << " s)\n";
        return 0;
    });
}
