// Stage 03 - intersect one ray per pixel with the scene's spheres and look at
// what it found: where the rays hit, the normals there, and how far away.
//
//     stage03_sphere scenes/spheres.scene -o spheres
//     stage03_sphere scenes/spheres.scene -o spheres --method stable
//
// Only spheres are intersected, by a flat loop over the scene's shapes that
// keeps the nearest hit (the course's "closest hit": each hit narrows tmax).
// Triangles and meshes are stage 04: they are skipped, and the program says
// how many it skipped.
//
// Writes, for PREFIX (default "stage03"):
//   PREFIX-hit.png     white where a ray hit a sphere, black where it missed
//   PREFIX-normal.png  the unit normal n at the hit as a color, (n + 1) / 2
//   PREFIX-normal.pfm  the normal itself, n in [-1, 1] per channel (0 0 0: miss)
//   PREFIX-depth.pfm   the distance from the eye to the hit, t |d|, in every channel (0: miss)
//   PREFIX-depth.png   depth as grey, linear from the nearest hit (white) to the farthest (1/4 grey)
// The PNGs are written without gamma (bytes proportional to the values shown);
// every file is written atomically.
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <rt/camera/camera.hpp>
#include <rt/intersection/sphere.hpp>
#include <rt/intersection/sphere_stable.hpp>
#include <rt/scene/scene.hpp>

#include "sphere_pass.hpp"
#include "stage_main.hpp"
#include "support.hpp"

namespace {

const char* usage =
    "usage: stage03_sphere SCENE [-o PREFIX] [--method textbook|stable] [--pixel I J]\n"
    "Intersects one ray per pixel with the scene's spheres (triangles and meshes are\n"
    "stage 04 and are skipped) and writes PREFIX-hit.png, PREFIX-normal.png,\n"
    "PREFIX-normal.pfm, PREFIX-depth.pfm and PREFIX-depth.png.\n"
    "  -o PREFIX        where to write (default stage03)\n"
    "  --method M       textbook: the course's quadratic (the stage-03 exercise, the default)\n"
    "                   stable: the library's method (Ray Tracing Gems ch. 7)\n"
    "  --pixel I J      tell the story of one pixel instead of writing images: its camera\n"
    "                   ray, every sphere it hits in loop order, the nearest hit and the\n"
    "                   values written; I is the column from the left, J the row from the top\n"
    "  --pixel-json I J the same as JSON (infinities are null)\n";

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage03_sphere", [&] {
        // parse
        stage::arguments args(argc, argv);
        std::string prefix = "stage03", method = "textbook";
        stage::pixel_request pixel;
        const std::optional<std::string> scene_file =
            stage::read_command_line(args, usage, "-o, --method, --pixel, --pixel-json", [&](const std::string& arg) {
                if (arg == "--method")
                    method = stage::parse_choice(arg, args.value_of(arg), {"textbook", "stable"});
                else
                    return stage::read_image_option(args, arg, prefix, pixel);
                return true;
            });
        if (!scene_file)
            return 0; // --help
        if (prefix.empty())
            throw stage::option_error("-o", "a file name prefix", prefix);
        const std::string& scene_path = *scene_file;
        const std::vector<std::string> names = {prefix + "-hit.png", prefix + "-normal.png", prefix + "-normal.pfm",
                                                prefix + "-depth.pfm", prefix + "-depth.png"};
        std::vector<std::filesystem::path> outputs;
        for (const std::string& name : names)
            outputs.push_back(stage::file_argument(name));
        if (!pixel.wanted)
            stage::check_writable_outputs(scene_path, "a scene file", outputs);

        // load: the spheres alone (triangles and meshes are stage 04's)
        const rt::scene s = stage::load_scene(scene_path);
        const std::uint64_t pixels = std::uint64_t(s.width) * std::uint64_t(s.height);
        if (!pixel.wanted) // five images of 12 bytes a pixel (three floats), and the PNGs' bytes
            stage::check_after_load(scene_path, s, outputs, pixels * (5 * 12 + 3),
                                    "five " + std::to_string(s.width) + "x" + std::to_string(s.height) + " images");
        const stage::sphere_set set = stage::spheres_of(s);
        const stage::sphere_hit_function hit = method == "stable" ? stage::sphere_hit_function(rt::hit_sphere)
                                                                  : stage::sphere_hit_function(rt::hit_sphere_textbook);
        const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
        if (pixel.wanted) {
            stage::tell_sphere_story(s, set, hit, method, gen, pixel);
            return 0;
        }

        // trace: one ray per pixel, the nearest hit of the loop over the spheres
        const stage::sphere_images out = stage::trace_spheres(set, hit, gen);

        // write: all five or none, every file complete before the first replaces its target
        stage::save_images({{names[0], &out.hits, 1.0f},
                            {names[1], &out.normals, 1.0f},
                            {names[2], &out.normal_values, 1.0f},
                            {names[3], &out.depths, 1.0f},
                            {names[4], &out.depth_view, 1.0f}});
        std::cerr << "stage03_sphere: " << set.spheres.size() << " sphere(s) intersected with the " << method
                  << " method";
        if (set.skipped_triangles + set.skipped_meshes > 0)
            std::cerr << "; skipped " << set.skipped_triangles << " triangle(s) and " << set.skipped_meshes
                      << " mesh(es) (stage 04)";
        std::cerr << "\n" << out.hit_count << " of " << pixels << " rays hit";
        if (out.hit_count > 0)
            std::cerr << ", depth " << out.nearest << " to " << out.farthest;
        std::cerr << "\nwrote " << names[0] << ", " << names[1] << ", " << names[2] << ", " << names[3] << ", "
                  << names[4] << "\n";
        return 0;
    });
}
