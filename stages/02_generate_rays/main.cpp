// Stage 02 - one ray per pixel, shown as an image of ray directions:
// (r, g, b) = (d/|d| + 1) / 2 (see include/rt/camera/ray_image.hpp).
//
//     stage02_generate_rays scenes/showcase.scene -o rays.png
//     stage02_generate_rays scenes/showcase.scene -o rays.ppm --projection orthographic
//     stage02_generate_rays scenes/showcase.scene --edge edge   (also edge-1.png, edge-16.png)
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <rt/camera/camera.hpp>
#include <rt/output/image_io.hpp>
#include <rt/system/path_text.hpp>
#include <rt/camera/ray_image.hpp>
#include <rt/input/scene_loader.hpp>

#include "edge.hpp"
#include "stage_main.hpp"
#include "support.hpp"

namespace {

const char* usage =
    "usage: stage02_generate_rays SCENE [-o OUTPUT] [--projection perspective|orthographic]\n"
    "Writes an image whose pixels show the direction of each pixel's ray.\n"
    "  -o OUTPUT       .png, .ppm or .pfm (default rays.png)\n"
    "  --strict        warnings of the OBJ files (missing materials) are errors\n"
    "  --projection P  override the scene camera's projection\n"
    "  --edge PREFIX   also PREFIX-1.png and PREFIX-16.png: an edge seen with one ray per pixel\n"
    "                  (its centre) and with 4 x 4 jittered samples averaged (your sampling)\n";

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage02_generate_rays", [&] {
        stage::arguments args(argc, argv);
        std::string output = "rays.png", edge_prefix;
        std::optional<rt::projection> projection; // the scene's unless --projection says otherwise
        bool strict = false;
        const std::optional<std::string> scene_file = stage::read_command_line(
            args, usage, "-o, --projection, --edge, --strict", [&](const std::string& arg) {
                if (arg == "-o") {
                    output = args.value_of("-o");
                } else if (arg == "--strict") { // missing materials, polygons not simple: errors, not warnings
                    strict = true;
                } else if (arg == "--projection") {
                    projection = stage::parse_name<rt::projection>(arg, args.value_of(arg), rt::projection_from_name,
                                                                  rt::detail::names_listed(rt::projection_names));
                } else if (arg == "--edge") {
                    edge_prefix = args.value_of("--edge");
                } else {
                    return false;
                }
                return true;
            });
        if (!scene_file)
            return 0; // --help
        const std::string& scene_path = *scene_file;
        std::vector<std::filesystem::path> outputs = {stage::file_argument(output)};
        if (!edge_prefix.empty()) {
            outputs.push_back(stage::file_argument(edge_prefix + "-1.png"));
            outputs.push_back(stage::file_argument(edge_prefix + "-16.png"));
            for (std::size_t k = 1; k < outputs.size(); ++k)
                if (std::filesystem::absolute(outputs[k]).lexically_normal() ==
                    std::filesystem::absolute(outputs[0]).lexically_normal())
                    throw rt::error("-o " + output + ": expected an output apart from the edge pictures, found " +
                                    rt::detail::utf8_text(outputs[k]) + " among them; choose another -o or --edge");
        }
        for (const std::filesystem::path& path : outputs) { // fail before the work, not after it
            rt::check_writable(path);
            rt::check_image_path(path);
        }
        stage::check_input_and_outputs(scene_path, "a scene file", outputs);

        rt::scene s = stage::load_scene(scene_path, strict);
        if (projection && *projection != s.cam.kind) { // the other projection: its own defaults
            s.cam.kind = *projection;
            s.cam.plane.reset();
            if (s.cam.kind == rt::projection::orthographic)
                s.cam.fov_degrees.reset();
        }
        // its OBJ and MTL files too; nothing is written yet
        rt::check_not_input(outputs, rt::files_read(stage::file_argument(scene_path), s));
        const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
        const rt::image rays = rt::render_ray_directions(gen);
        if (edge_prefix.empty()) {
            stage::save_image(output, rays, 1.0f);
        } else {
            const stage::edge_pictures edge = stage::render_edge(gen);
            stage::save_images({{output, &rays, 1.0f},
                                {edge_prefix + "-1.png", &edge.centre, 1.0f},
                                {edge_prefix + "-16.png", &edge.sixteen, 1.0f}}); // all three or none
            // the RMS difference from the exact fraction of each pixel above the edge (edge.hpp)
            std::fprintf(stderr,
                         "edge: %d pixels on the edge, RMS error of their values: 1 ray at the centre %.4f, "
                         "1 jittered sample %.4f, 16 jittered samples (4 x 4, box) %.4f\n",
                         edge.edge_pixels, edge.rms_centre, edge.rms_one, edge.rms_sixteen);
        }
        // then what stage 02 computed from the camera: the frame and the window (FCG sec. 4.3)
        std::fprintf(stderr, "e %g %g %g\nu %g %g %g\nv %g %g %g\nw %g %g %g\nwindow l %g r %g b %g t %g, d %g\n",
                     double(gen.e.x), double(gen.e.y), double(gen.e.z), double(gen.basis.u.x),
                     double(gen.basis.u.y), double(gen.basis.u.z), double(gen.basis.v.x), double(gen.basis.v.y),
                     double(gen.basis.v.z), double(gen.basis.w.x), double(gen.basis.w.y), double(gen.basis.w.z),
                     double(gen.plane.l), double(gen.plane.r), double(gen.plane.b), double(gen.plane.t),
                     double(gen.d));
        std::cerr << "wrote " << output << " (" << s.width << "x" << s.height << " ray directions)";
        if (!edge_prefix.empty())
            std::cerr << ", " << outputs[1].string() << " and " << outputs[2].string() << " (the edge)";
        std::cerr << '\n';
        return 0;
    });
}
