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
#include <iostream>
#include <optional>
#include <string>

#include <rt/output/aov.hpp>
#include <rt/rendering/progress.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/scene/scene.hpp>
#include <rt/system/platform.hpp>

#include "pixel_story.hpp"
#include "render_arguments.hpp"
#include "render_command.hpp"
#include "stage_main.hpp"
#include "support.hpp"
#include "support_frame.hpp"

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

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage08_output", [&] {
        stage::arguments args(argc, argv);
        const std::optional<stage::render_command> arguments = stage::read_render_command(args, usage);
        if (!arguments)
            return 0; // --help
        const stage::render_command& set = *arguments;
        const stage::render_settings& render = set.render;
        stage::check_render_command(set);

        // load
        rt::scene scene;
        if (set.pattern != stage::pattern_kind::none)
            scene.width = scene.height = 512;
        else
            scene = stage::load_render_input(render); // with --camera and --max-depth applied
        if (set.pattern == stage::pattern_kind::none)
            rt::check_not_input(stage::file_argument(set.output),
                               rt::files_read(stage::file_argument(render.input), scene)); // its OBJ and MTL files too

        rt::render_options options = stage::render_options_for(render, scene);
        options.crop = set.crop;
        rt::check_render_options(options);
        stage::check_memory_for_image(options, set.output);

        if (set.pixel.wanted) {
            // the ray through the pixel's centre, traced by the stage-07 color function
            stage::story st = stage::shaded_story(scene, "stage08_output", set.pixel.column, set.pixel.row,
                                                  options.width, options.height);
            stage::add_encoding_story(st, render.encoding, options.samples_per_pixel);
            if (set.pixel.json)
                stage::print_story_json(std::cout, st, scene);
            else
                stage::print_story(std::cout, st, scene);
            return 0;
        }

        // render: the renderer, the BVH and the stage-07 color are compiled once
        // (support_frame.cpp): an edit to a stage-08 exercise rebuilds none of them
        rt::progress_bar bar(std::cerr, !set.quiet && rt::detail::stderr_is_terminal());
        const rt::render_result result =
            set.pattern != stage::pattern_kind::none
                ? stage::render_image(
                      options, [](rt::real x, rt::real y) { return rt::ray{rt::vec3(x, y, 0), rt::vec3(0, 0, -1)}; },
                      stage::make_pattern(set.pattern, options.width, options.height), bar.callback())
                : stage::render_scene(scene, render.aov, options, bar.callback());
        bar.finish();

        // write
        stage::save_encoded(set.output, result.pixels, render.aov, render.encoding);
        if (!set.quiet) {
            std::cerr << "wrote " << set.output << ": " << rt::summary_line(result.stats) << " ("
                      << rt::name_of(options.sampler) << ", " << rt::name_of(options.reconstruction.kind) << " "
                      << options.reconstruction.radius << ")";
            if (set.pattern == stage::pattern_kind::none && render.aov != rt::aov_kind::rays) // the BVH traced it
                std::cerr << ", BVH " << stage::simd_path();
            std::cerr << "\n";
        }
        return 0;
    });
}
