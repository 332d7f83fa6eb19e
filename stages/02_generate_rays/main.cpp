// Stage 02 - one ray per pixel, shown as an image of ray directions:
// (r, g, b) = (d/|d| + 1) / 2 (see include/rt/ray_image.hpp).
//
//     stage02_generate_rays scenes/showcase.scene -o rays.png
//     stage02_generate_rays scenes/showcase.scene -o rays.ppm --projection orthographic
#include <cstdio>
#include <iostream>
#include <string>

#include <rt/camera.hpp>
#include <rt/image_io.hpp>
#include <rt/ray_image.hpp>
#include <rt/scene_loader.hpp>

#include "stage_main.hpp"
#include "support.hpp"

namespace {

const char* usage =
    "usage: stage02_generate_rays SCENE [-o OUTPUT] [--projection perspective|orthographic]\n"
    "Writes an image whose pixels show the direction of each pixel's ray.\n"
    "  -o OUTPUT       .png, .ppm or .pfm (default rays.png)\n"
    "  --strict        warnings of the OBJ files (missing materials) are errors\n"
    "  --projection P  override the scene camera's projection\n";

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage02_generate_rays", [&] {
        stage::arguments args(argc, argv);
        std::string scene_path, output = "rays.png", projection;
        bool strict = false;
        while (!args.done()) {
            const std::string arg = args.take();
            if (arg == "--help" || arg == "-h") {
                std::cout << usage;
                return 0;
            } else if (arg == "-o") {
                output = args.value_of("-o");
            } else if (arg == "--strict") { // missing materials, polygons not simple: errors, not warnings
                strict = true;
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

        rt::scene s = stage::load_scene(scene_path, strict);
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
        stage::save_image(output, rt::render_ray_directions(gen), 1.0f);
        // then what stage 02 computed from the camera: the frame and the window (FCG sec. 4.3)
        std::fprintf(stderr, "e %g %g %g\nu %g %g %g\nv %g %g %g\nw %g %g %g\nwindow l %g r %g b %g t %g, d %g\n",
                     double(gen.e.x), double(gen.e.y), double(gen.e.z), double(gen.basis.u.x),
                     double(gen.basis.u.y), double(gen.basis.u.z), double(gen.basis.v.x), double(gen.basis.v.y),
                     double(gen.basis.v.z), double(gen.basis.w.x), double(gen.basis.w.y), double(gen.basis.w.z),
                     double(gen.plane.l), double(gen.plane.r), double(gen.plane.b), double(gen.plane.t),
                     double(gen.d));
        std::cerr << "wrote " << output << " (" << s.width << "x" << s.height << " ray directions)\n";
        return 0;
    });
}
