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
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <ctime>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/system/atomic_file.hpp>
#include <rt/camera/camera.hpp>
#include <rt/intersection/hit_list.hpp>
#include <rt/system/parallel.hpp>

#include "pixel_story.hpp"
#include "stage_main.hpp"
#include "support.hpp"
#include "textbook_groups.hpp"
#include "textbook_list.hpp"

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

using clock_type = std::chrono::steady_clock;

double seconds_since(clock_type::time_point start)
{
    return std::chrono::duration<double>(clock_type::now() - start).count();
}

bool ends_with(const std::string& text, const std::string& tail)
{
    return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

/// What one ray found, for the images: the normal shown and the distance t |d|.
struct pixel_hit {
    bool hit = false;
    std::uint32_t shape = 0;
    rt::vec3 normal{0};
    float depth = 0;
};

template <class Accelerator>
pixel_hit trace_one(const Accelerator& world, const rt::ray& r, bool geometric)
{
    pixel_hit out;
    rt::hit_record rec;
    if (!world.closest_hit(r, 0, rt::infinity, rec))
        return out;
    out.hit = true;
    out.shape = rec.shape;
    out.normal = geometric ? rec.geometric_normal : rec.normal;
    out.depth = float(rec.t * glm::length(r.direction));
    return out;
}

/// Every pixel's hit, the top row first, traced on every core (rt::parallel_for
/// over the rows; each row writes only its own slots). With row_step > 1 only
/// the rows j = 0, row_step, 2 row_step, ... are traced (a sample, for timing);
/// the other pixels stay misses. An exception (an exercise not done yet, say)
/// is thrown again here once every thread has stopped.
template <class Accelerator>
std::vector<pixel_hit> trace_image(const Accelerator& world, const rt::ray_generator& gen, bool geometric,
                                   int row_step = 1)
{
    std::vector<pixel_hit> hits(std::size_t(gen.nx) * std::size_t(gen.ny));
    const std::size_t rows = std::size_t((gen.ny + row_step - 1) / row_step);
    rt::parallel_for(rows, rt::thread_count(0), [&](std::size_t row, int) {
        const int j = int(row) * row_step;
        for (int i = 0; i < gen.nx; ++i)
            hits[std::size_t(gen.ny - 1 - j) * std::size_t(gen.nx) + std::size_t(i)] =
                trace_one(world, rt::pixel_ray(gen, i, j), geometric);
    });
    return hits;
}

rt::image picture_of(const std::vector<pixel_hit>& hits, int width, int height, const std::string& mode, bool raw)
{
    rt::image img(width, height);
    float nearest = std::numeric_limits<float>::infinity(), farthest = 0;
    for (const pixel_hit& h : hits)
        if (h.hit) {
            nearest = std::min(nearest, h.depth);
            farthest = std::max(farthest, h.depth);
        }
    for (std::size_t k = 0; k < hits.size(); ++k) {
        if (!hits[k].hit)
            continue; // black where the ray missed
        if (mode != "depth")
            img.pixels[k] = rt::color((hits[k].normal + rt::vec3(1)) * rt::real(0.5));
        else if (raw)
            img.pixels[k] = rt::color(hits[k].depth);
        else
            img.pixels[k] = rt::color(1.0f - 0.8f * (hits[k].depth - nearest) /
                                                 (farthest > nearest ? farthest - nearest : 1.0f)); // near white, far grey
    }
    return img;
}

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage04_triangle", [&] {
        stage::arguments args(argc, argv);
        std::string output = "triangle.png", mode = "normals", accel = "groups";
        int width = 0, height = 0;
        bool compare = false, strict = false;
        stage::pixel_request pixel;
        const std::optional<std::string> input_file = stage::read_command_line(
            args, usage, "-o, --mode, --size, --accel, --compare, --pixel, --pixel-json, --strict",
            [&](const std::string& arg) {
                if (arg == "--mode") {
                    mode = stage::parse_choice(arg, args.value_of(arg), {"normals", "geometric", "depth"});
                } else if (arg == "--size") {
                    const std::string size = args.value_of(arg);
                    const std::size_t x = size.find('x');
                    if (x == std::string::npos)
                        throw stage::option_error(arg, "WxH such as 800x600", size);
                    width = int(stage::parse_integer("--size (width)", size.substr(0, x), 1, 16384));
                    height = int(stage::parse_integer("--size (height)", size.substr(x + 1), 1, 16384));
                } else if (arg == "--accel") {
                    accel = args.value_of("--accel");
                    if (accel != "list" && accel != "groups")
                        rt::parse_accelerator_kind(accel); // an rt::error naming the choices
                } else if (arg == "--strict") { // missing materials, polygons not simple: errors, not warnings
                    strict = true;
                } else if (arg == "--compare") {
                    compare = true;
                } else {
                    return stage::read_image_option(args, arg, output, pixel);
                }
                return true;
            },
            "an OBJ or scene file");
        if (!input_file)
            return 0; // --help
        const std::string& input = *input_file;
        if (!pixel.wanted) {
            stage::check_image_output(output); // every option, the output format included, before any work
            stage::check_input_and_outputs(input, ends_with(input, ".scene") ? "a scene file" : "an OBJ file",
                                           {stage::file_argument(output)});
        }

        const auto load_start = clock_type::now();
        rt::scene s = width > 0 ? stage::load_input(input, width, height, strict)
                                : stage::load_input(input, std::nullopt, std::nullopt, strict);
        if (!pixel.wanted)
            rt::check_not_input(stage::file_argument(output), // its OBJ and MTL files too
                                rt::files_read(stage::file_argument(input), s));
        if (width == 0) {
            width = s.width;
            height = s.height;
        }
        const stage::shape_counts n = stage::count_shapes(s);
        if (!pixel.wanted) // the story alone on stdout, so --pixel-json stays JSON
            std::cout << input << ": " << n.spheres << " sphere(s), " << n.triangles << " triangle(s), " << n.meshes
                      << " mesh(es) of " << n.mesh_triangles << " triangle(s) (load " << std::setprecision(3)
                      << seconds_since(load_start) << " s)\n";
        const rt::ray_generator gen = rt::make_ray_generator(s.cam, width, height);
        const stage::textbook_list list{&s};

        if (pixel.wanted) {
            stage::story st;
            st.program = "stage04_triangle";
            stage::place_pixel(st, pixel.column, pixel.row, gen.nx, gen.ny);
            st.camera = rt::pixel_ray(gen, st.i, st.j);
            rt::hit_record rec;
            stage::recording<stage::textbook_list>(list, st.queries).closest_hit(st.camera, 0, rt::infinity, rec);
            stage::name_queries(st);
            st.values.push_back({"method:", "your closest_hit_list with hit_triangle_moller_trumbore and hit_sphere_textbook"});
            const stage::world library(s, "auto");
            rt::hit_record reference;
            const bool library_hit = library.closest_hit(st.camera, 0, rt::infinity, reference);
            st.values.push_back({"the library's BVH:", library_hit ? "hits shape " + std::to_string(reference.shape) +
                                                                         " at t " + std::to_string(reference.t)
                                                                   : std::string("misses")});
            if (!st.queries.empty() && st.queries[0].hit)
                st.linear = rt::color((st.queries[0].rec.normal + rt::vec3(1)) * rt::real(0.5));
            if (pixel.json)
                stage::print_story_json(std::cout, st, s);
            else
                stage::print_story(std::cout, st, s);
            return 0;
        }

        const bool geometric = mode == "geometric";
        const bool raw = ends_with(output, ".pfm");
        const std::size_t primitives = n.spheres + n.triangles + n.mesh_triangles;
        const double tests = double(primitives) * double(width) * double(height);
        // your code: the groups (the default) or the list; the library: its BVH or flat list
        const bool use_list = accel == "list";
        const bool use_groups = accel == "groups" || (compare && !use_list);
        const bool mine_shown = use_list || accel == "groups";
        const std::string yours = use_list ? "your list" : "your groups";
        // the list tests every shape for every ray: about 10 ns a test here, so
        // beyond a few billion tests it would take minutes (the bunny at 640x480: 21 billion)
        if (use_list && tests > 3e9)
            throw rt::error("expected a scene the list can trace in a minute, found " + std::to_string(primitives) +
                            " shapes for each of " + std::to_string(width * height) + " rays (" +
                            std::to_string(tests / 1e9).substr(0, 5) +
                            " billion tests); try --size 160x120, --accel groups for your groups, or --accel bvh "
                            "for the library's BVH");

        // the pixels traced with `world` (every row_step-th row), timed, and one line:
        // how many hit, how fast; the rate in rays per second goes to `rate`
        auto trace_timed = [&](const auto& world, const std::string& name, int row_step, double& rate) {
            const auto start = clock_type::now();
            std::vector<pixel_hit> hits = trace_image(world, gen, geometric, row_step);
            const double seconds = seconds_since(start);
            const std::size_t rays = std::size_t((gen.ny + row_step - 1) / row_step) * std::size_t(gen.nx);
            std::size_t count = 0;
            for (const pixel_hit& h : hits)
                count += h.hit ? 1 : 0;
            rate = double(rays) / std::max(seconds, 1e-9);
            std::cout << name << ": " << count << " of " << rays << " rays hit, " << std::setprecision(3) << seconds
                      << " s (" << rate / 1e6 << " Mrays/s)\n";
            return hits;
        };
        std::vector<pixel_hit> mine, library;
        double mine_rate = 0, list_rate = 0, library_rate = 0;
        if (use_list)
            mine = trace_timed(list, "your list", 1, mine_rate);
        if (use_groups) {
            const auto build_start = clock_type::now();
            const stage::textbook_groups groups(s);
            std::ostringstream name;
            name << "your groups (" << groups.g.items.size() << " items, " << groups.g.nodes.size()
                 << " nodes, built in " << std::setprecision(3) << seconds_since(build_start) << " s)";
            mine = trace_timed(groups, name.str(), 1, mine_rate);
            // the speed-up over your list, timed on one row in `step` when the whole
            // image would take the list more than 1e8 tests (a few seconds)
            const int step = int(std::min(double(height), std::max(1.0, std::ceil(tests / 1e8))));
            const std::string list_name =
                step == 1 ? std::string("your list") : "your list (one row in " + std::to_string(step) + ")";
            trace_timed(list, list_name, step, list_rate);
            std::ostringstream speed_up;
            speed_up << std::fixed << std::setprecision(1) << mine_rate / list_rate;
            std::cout << "your groups' speed-up over your list: " << speed_up.str() << "x\n";
        }
        if (!mine_shown || use_groups || compare) {
            const auto build_start = clock_type::now();
            const stage::world world(s, mine_shown ? "auto" : accel);
            std::ostringstream name;
            name << "the library (" << world.kind() << " over " << world.primitives() << " primitives";
            if (world.kind() == "bvh")
                name << ", " << world.nodes() << " nodes";
            name << ", built in " << std::setprecision(3) << seconds_since(build_start) << " s)";
            library = trace_timed(world, name.str(), 1, library_rate);
        }

        // where your image and the library's differ
        rt::image diff(width, height);
        std::size_t leaks = 0, extra = 0, other = 0;
        if (!mine.empty() && !library.empty()) {
            for (std::size_t k = 0; k < mine.size(); ++k) {
                const pixel_hit& a = mine[k];
                const pixel_hit& b = library[k];
                if (b.hit && !a.hit) {
                    ++leaks;
                    diff.pixels[k] = rt::color(1, 0, 0);
                } else if (a.hit && !b.hit) {
                    ++extra;
                    diff.pixels[k] = rt::color(0, 0, 1);
                } else if (a.hit && (a.shape != b.shape ||
                                     std::fabs(a.depth - b.depth) > 1e-4f * std::max(a.depth, b.depth))) {
                    ++other;
                    diff.pixels[k] = rt::color(1, 1, 0);
                } else if (a.hit) {
                    diff.pixels[k] = rt::color(0.25f); // the same hit
                }
            }
            std::cout << yours << " against the library's: " << leaks + extra + other << " of " << mine.size()
                      << " pixels differ (" << leaks << " leaked through your triangles: the library hits, yours "
                      << "misses; " << extra << " hit only with yours; " << other
                      << " hit a different shape or depth)\n";
        }
        if (compare) {
            stage::save_image(output, diff, 1.0f);
            std::cout << "wrote " << output << " (red: leaks, blue: only yours, yellow: different, grey: the same)\n";
            return 0;
        }
        stage::save_image(output, picture_of(mine_shown ? mine : library, width, height, mode, raw), 1.0f);
        std::cout << "wrote " << output << " (" << mode << ", " << (mine_shown ? yours : "the library's " + accel)
                  << ")\n";
        return 0;
    });
}
