// Stage 04 - triangles, meshes, the list and the groups: render a scene or an
// OBJ model as normals or depth with the student's own code (Moller-Trumbore
// for triangles, the textbook quadratic for spheres, the groups of
// rt::build_groups and rt::closest_hit_groups, or the list of
// rt::closest_hit_list), time the groups against the list, and compare the
// image with the library's watertight BVH.
//
//     stage04_triangle scenes/showcase.scene -o showcase.png
//     stage04_triangle ../shared/meshes/stanford-bunny.obj --size 160x120 -o bunny.png
//     stage04_triangle ../shared/meshes/stanford-bunny.obj --accel bvh -o bunny.png
//     stage04_triangle scenes/showcase.scene --compare -o differences.png
//     stage04_triangle scenes/showcase.scene --pixel 320 200
#include <iostream>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <rt/camera/camera.hpp>

#include "stage_main.hpp"
#include "support.hpp"
#include "textbook_list.hpp"
#include "triangle_pass.hpp"

namespace {

const char* usage =
    "usage: stage04_triangle INPUT [-o OUTPUT] [--mode normals|geometric|depth] [--size WxH]\n"
    "                        [--accel groups|list|flat|bvh|auto] [--compare] [--pixel I J]\n"
    "Renders INPUT, a .scene file (its camera and shapes) or a bare OBJ model (framed\n"
    "by its bounds), one ray per pixel, and prints how long it took.\n"
    "  -o OUTPUT       .png, .ppm or .pfm (default triangle.png); a .pfm of depth holds t |d|\n"
    "  --mode M        normals: (n + 1)/2 of the shading normal (default); geometric: of the\n"
    "                  geometric normal; depth: distance, near white, far grey\n"
    "  --size WxH      image size (default: the scene's own; 640x480 for an OBJ)\n"
    "  --accel A       groups: your build_groups and closest_hit_groups with your\n"
    "                  hit_triangle_moller_trumbore and hit_sphere_textbook (the default; it\n"
    "                  also times your list on a sample of the rows and prints the speed-up,\n"
    "                  and counts the pixels that differ from the library's BVH);\n"
    "                  list: your closest_hit_list with the same methods;\n"
    "                  flat, bvh, auto: the library's watertight test and BVH\n"
    "  --compare       render with yours (your groups; your list with --accel list) and the\n"
    "                  library's, and write where they differ: red where only the\n"
    "                  library hits (a ray that leaked through your triangles), blue where\n"
    "                  only yours hits, yellow where both hit different shapes or depths\n"
    "  --strict        warnings of the OBJ files (missing materials) are errors\n"
    "  --pixel I J      tell the story of one pixel (your list): its camera ray and hit;\n"
    "                   I is the column from the left, J the row from the top\n"
    "  --pixel-json I J the same as JSON (infinities are null)\n";

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage04_triangle", [&] {
        // parse
        stage::arguments args(argc, argv);
        std::string output = "triangle.png", mode = "normals", accel = "groups";
        int width = 0, height = 0;
        bool compare = false, strict = false;
        stage::pixel_request pixel;
        const std::optional<std::string> input_file = stage::read_command_line(
            args, usage, "-o, --mode, --size, --accel, --compare, --pixel, --pixel-json, --strict",
            [&](const std::string& arg) {
                if (arg == "--mode")
                    mode = stage::parse_choice(arg, args.value_of(arg), {"normals", "geometric", "depth"});
                else if (arg == "--size")
                    stage::parse_size(arg, args.value_of(arg), width, height);
                else if (arg == "--accel")
                    accel = stage::parse_choice(arg, args.value_of(arg), {"groups", "list", "flat", "bvh", "auto"});
                else if (arg == "--strict") // missing materials, polygons not simple: errors, not warnings
                    strict = true;
                else if (arg == "--compare")
                    compare = true;
                else
                    return stage::read_image_option(args, arg, output, pixel);
                return true;
            },
            "an OBJ or scene file");
        if (!input_file)
            return 0; // --help
        const std::string& input = *input_file;
        if (!pixel.wanted) {
            stage::check_image_output(output); // every option, the output format included, before any work
            const bool scene_file = stage::file_argument(input).extension() == ".scene";
            stage::check_input_and_outputs(input, scene_file ? "a scene file" : "an OBJ file",
                                           {stage::file_argument(output)});
        }

        // load
        const auto load_start = stage::clock_type::now();
        rt::scene s = width > 0 ? stage::load_input(input, width, height, strict)
                                : stage::load_input(input, std::nullopt, std::nullopt, strict);
        width = width > 0 ? width : s.width;
        height = height > 0 ? height : s.height;
        if (pixel.wanted) {
            stage::tell_triangle_story(s, rt::make_ray_generator(s.cam, width, height), pixel);
            return 0;
        }
        rt::check_not_input(stage::file_argument(output), rt::files_read(stage::file_argument(input), s));
        const stage::shape_counts n = stage::count_shapes(s);
        stage::print_shape_counts(input, n, stage::seconds_since(load_start));
        const rt::ray_generator gen = rt::make_ray_generator(s.cam, width, height);

        // trace: your code (the groups, the default, or the list), then the library's BVH or flat list
        const bool geometric = mode == "geometric", use_list = accel == "list";
        const bool use_groups = accel == "groups" || (compare && !use_list);
        const bool mine_shown = use_list || accel == "groups";
        const std::string yours = use_list ? "your list" : "your groups";
        const std::size_t primitives = n.spheres + n.triangles + n.mesh_triangles;
        std::vector<stage::pixel_hit> mine, library;
        if (use_list) {
            stage::check_list_is_quick_enough(primitives, width, height);
            mine = stage::trace_timed(stage::textbook_list{&s}, "your list", gen, geometric).hits;
        }
        if (use_groups)
            mine = stage::trace_groups_and_list(s, gen, geometric, primitives);
        if (!mine_shown || use_groups || compare)
            library = stage::trace_library(s, gen, geometric, mine_shown ? "auto" : accel);

        // write: the picture of your hits (or the library's), or where the two differ
        const rt::image diff = !mine.empty() && !library.empty()
                                   ? stage::difference(mine, library, width, height, yours)
                                   : rt::image(width, height);
        const bool raw = stage::file_argument(output).extension() == ".pfm";
        const rt::image shown = stage::picture_of(mine_shown ? mine : library, width, height, mode, raw);
        stage::save_image(output, compare ? diff : shown, 1.0f);
        std::cout << "wrote " << output
                  << (compare ? " (red: leaks, blue: only yours, yellow: different, grey: the same)"
                              : " (" + mode + ", " + (mine_shown ? yours : "the library's " + accel) + ")")
                  << "\n";
        return 0;
    });
}
