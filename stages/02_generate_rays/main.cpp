// Stage 02 - one ray per pixel, shown as an image of ray directions:
// (r, g, b) = (d/|d| + 1) / 2 (see include/rt/ray_image.hpp).
//
//     stage02_generate_rays scenes/showcase.scene -o rays.png
//     stage02_generate_rays scenes/showcase.scene -o rays.ppm --projection orthographic
#include <iostream>
#include <string>

#include <rt/camera.hpp>
#include <rt/image_io.hpp>
#include <rt/ray_image.hpp>
#include <rt/scene_loader.hpp>

#include "stage_main.hpp"

namespace {

const char* usage =
    "usage: stage02_generate_rays SCENE [-o OUTPUT] [--projection perspective|orthographic]\n"
    "Writes an image whose pixels show the direction of each pixel's ray.\n"
    "  -o OUTPUT       .png, .ppm or .pfm (default rays.png)\n"
    "  --projection P  override the scene camera's projection\n";

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage02_generate_rays", [&] {
        stage::arguments args(argc, argv);
        std::string scene_path, output = "rays.png", projection;
        while (!args.done()) {
            const std::string arg = args.take();
            if (arg == "--help" || arg == "-h") {
                std::cout << usage;
                return 0;
            } else if (arg == "-o") {
                output = args.value_of("-o");
            } else if (arg == "--projection") {
                projection = args.value_of("--projection");
                if (projection != "perspective" && projection != "orthographic")
                    throw rt::error("--projection: expected perspective or orthographic, found '" + projection + "'");
            } else if (!arg.empty() && arg[0] == '-') {
                throw rt::error("expected an option (-o, --projection, --help), found '" + arg + "'; see --help");
            } else if (scene_path.empty()) {
                scene_path = arg;
            } else {
                throw rt::error("expected one scene file, found also '" + arg + "'; see --help");
            }
        }
        if (scene_path.empty())
            throw rt::error("expected a scene file, found none; see --help");
        rt::check_writable(output); // fail before the work, not after it
        rt::check_image_path(output);
        stage::check_input_and_outputs(scene_path, "a scene file", {output});

        rt::scene s = rt::load_scene(scene_path);
        if (projection == "orthographic" && s.cam.kind != rt::projection::orthographic) {
            s.cam.kind = rt::projection::orthographic;
            s.cam.fov_degrees.reset();
            s.cam.plane.reset();
        } else if (projection == "perspective" && s.cam.kind != rt::projection::perspective) {
            s.cam.kind = rt::projection::perspective;
            s.cam.plane.reset();
        }
        rt::check_not_input(output, rt::files_read(scene_path, s)); // its OBJ and MTL files too; nothing is written yet
        const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
        rt::save_image(output, rt::render_ray_directions(gen), 1.0f);
        std::cerr << "wrote " << output << " (" << s.width << "x" << s.height << " ray directions)\n";
        return 0;
    });
}
