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

#include "path_story_text.hpp"
#include "stage_main.hpp"
#include "support.hpp"

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
            stage::tell_path_story(std::cout, s, accel, lights, rays, seed, pixel, options.path);
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
