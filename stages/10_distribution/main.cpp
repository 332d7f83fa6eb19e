// Stage 10 - distribution ray tracing: soft shadows from area lights, glossy
// mirrors, depth of field (include/rt/scene/area_light.hpp, glossy.hpp, thin_lens.hpp).
// Each pixel averages many samples, and each sample draws its own point of the
// lens, of every area light and of every glossy reflection.
//
//     stage10_distribution scenes/soft.scene -o soft.png [--spp N] [--pixel I J]
//
// The image is rt::render's (stage 08) of rt::make_radiance's color, compiled
// once in stages/common/support_frame.cpp: that file includes this stage's
// headers, so an edit to them rebuilds it and this program only.
#include <cstdint>
#include <iostream>
#include <optional>
#include <string>

#include <rt/system/atomic_file.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/rendering/sampler.hpp>
#include <rt/scene/scene.hpp>

#include "pixel_story.hpp"
#include "stage_main.hpp"
#include "support.hpp"
#include "support_frame.hpp"

int main(int argc, char** argv)
{
    return stage::run("stage10_distribution", [&] {
        stage::arguments args(argc, argv);
        std::string output = "distribution.png";
        int spp = 0;
        std::uint64_t seed = 0;
        stage::pixel_request pixel;
        const std::string usage =
            std::string("usage: stage10_distribution SCENE [-o OUTPUT] [--spp N] [--seed S]\n"
                        "Renders SCENE with area lights, glossy mirrors and a thin lens, averaging\n"
                        "N jittered samples per pixel, each with its own random numbers.\n"
                        "  -o OUTPUT    .png, .ppm or .pfm (default distribution.png)\n"
                        "  --spp N      samples per pixel, 1..65536 (default: the scene's samples)\n"
                        "  --seed S     the random numbers' seed (default 0): another seed, other noise\n") +
            stage::pixel_help;
        const std::optional<std::string> scene_path = stage::read_command_line(
            args, usage, "-o, --spp, --seed, --pixel, --pixel-json", [&](const std::string& arg) {
                if (arg == "--spp")
                    spp = int(stage::parse_integer(arg, args.value_of(arg), 1, 1 << 16));
                else if (arg == "--seed")
                    seed = std::uint64_t(stage::parse_integer(arg, args.value_of(arg), 0, 1LL << 62));
                else
                    return stage::read_image_option(args, arg, output, pixel);
                return true;
            });
        if (!scene_path)
            return 0; // --help
        if (!pixel.wanted) {
            stage::check_image_output(output); // every option, the output format included, before any work
            stage::check_input_and_outputs(*scene_path, "a scene file", {stage::file_argument(output)});
        }
        const rt::scene s = stage::load_scene(*scene_path);
        if (pixel.wanted) {
            // one sample of the pixel: its centre, with the random numbers of the render's first sample
            const stage::story st = stage::shaded_story(s, "stage10_distribution", pixel.column, pixel.row, s.width, s.height);
            if (pixel.json)
                stage::print_story_json(std::cout, st, s);
            else
                stage::print_story(std::cout, st, s);
            return 0;
        }
        rt::check_not_input(stage::file_argument(output), // its OBJ and MTL files too
                            rt::files_read(stage::file_argument(*scene_path), s));
        rt::render_options options;
        options.width = s.width;
        options.height = s.height;
        options.samples_per_pixel = spp > 0 ? spp : s.samples;
        options.sampler = rt::sampler_kind::jittered;
        options.seed = seed;
        const rt::render_result out = stage::render_scene(s, rt::aov_kind::shaded, options, {});
        stage::save_image(output, out.pixels, 2.2f);
        const int samples = rt::effective_samples(options.sampler, options.samples_per_pixel);
        std::cerr << "stage10_distribution: wrote " << output << " (" << s.width << "x" << s.height << ", " << samples
                  << (samples == 1 ? " sample" : " samples") << " per pixel)\n";
        return 0;
    });
}
