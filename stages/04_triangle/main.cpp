// Stage 04 - triangles, meshes and groups: render an OBJ mesh (or a scene's
// shapes) as normals or depth, through the scene-level intersection
// (include/rt/intersect.hpp), and report what the BVH costs and buys.
//
//     stage04_triangle ../shared/meshes/stanford-bunny.obj -o bunny.png
//     stage04_triangle ../shared/meshes/stanford-bunny.obj --mode depth -o depth.pfm
//     stage04_triangle scenes/showcase.scene --accel flat -o showcase.png
//     stage04_triangle --crossover          # measure where the BVH beats the flat list
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <ctime>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include <rt/camera.hpp>
#include <rt/image_io.hpp>
#include <rt/intersect.hpp>
#include <rt/obj_loader.hpp>
#include <rt/scene_loader.hpp>

#include "stage_main.hpp"

namespace {

const char* usage =
    "usage: stage04_triangle INPUT [-o OUTPUT] [--mode normals|geometric|depth] [--size WxH]\n"
    "                        [--accel flat|bvh|auto] [--view X Y Z] [--repeat N]\n"
    "       stage04_triangle --crossover\n"
    "Renders INPUT, an OBJ mesh (seen from outside, framed by its bounds) or a .scene\n"
    "file (its camera and shapes), one ray per pixel, and prints the build time, the\n"
    "BVH's size and the rays per second of one thread.\n"
    "  -o OUTPUT       .png, .ppm or .pfm (default triangle.png); a .pfm of depth holds t\n"
    "  --mode M        normals: (n + 1)/2 of the shading normal (default); geometric: of the\n"
    "                  geometric normal; depth: distance, near white, far grey (.pfm: the distance)\n"
    "  --size WxH      image size (default 800x600 for a mesh, the scene's own for a scene)\n"
    "  --accel A       flat, bvh or auto (default auto)\n"
    "  --view X Y Z    direction from the mesh's centre to the camera (default 0 0 1)\n"
    "  --repeat N      trace the image N times and report the fastest (default 1)\n"
    "  --crossover     time the flat list against the BVH for 1 to 256 primitives\n";

using clock_type = std::chrono::steady_clock;

double seconds_since(clock_type::time_point start)
{
    return std::chrono::duration<double>(clock_type::now() - start).count();
}

/// The processor time this program has used: unlike the wall clock, it does
/// not count the time other programs on a busy machine took the core away.
/// Tracing runs on one thread, so this is that thread's time.
double cpu_seconds()
{
    return double(std::clock()) / CLOCKS_PER_SEC;
}

int parse_int(const std::string& text, const std::string& what, int low, int high)
{
    std::size_t used = 0;
    int value = 0;
    try {
        value = std::stoi(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || value < low || value > high)
        throw rt::error(what + ": expected a whole number between " + std::to_string(low) + " and " +
                        std::to_string(high) + ", found '" + text + "'");
    return value;
}

rt::real parse_real(const std::string& text, const std::string& what)
{
    std::size_t used = 0;
    double value = 0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || !std::isfinite(value))
        throw rt::error(what + ": expected a number, found '" + text + "'");
    return rt::real(value);
}

bool ends_with(const std::string& text, const std::string& tail)
{
    return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

/// A perspective camera looking at the box's centre from direction `view`,
/// as close as it can be while all eight corners stay inside the image (a 30
/// degree vertical field of view, with a 5% margin). For a corner q (relative
/// to the centre) at depth z = q.w and offsets x = q.u, y = q.v on the image
/// plane axes, the camera at distance D along w sees it inside the window when
/// |x| <= (D - z) tan(fov_x / 2) and |y| <= (D - z) tan(fov_y / 2).
rt::camera frame_box(const rt::aabb& box, rt::vec3 view, int width, int height)
{
    const rt::real fov = 30;
    const rt::real tan_y = std::tan(fov * rt::real(3.14159265358979323846) / 360);
    const rt::real tan_x = tan_y * rt::real(width) / rt::real(height);
    const rt::vec3 c = box.center();
    rt::camera cam;
    cam.kind = rt::projection::perspective;
    cam.up = std::fabs(glm::normalize(view).y) > rt::real(0.99) ? rt::vec3(0, 0, 1) : rt::vec3(0, 1, 0);
    const rt::frame axes = rt::make_frame(c + view, c, cam.up);
    rt::real distance = rt::real(1e-6);
    for (int corner = 0; corner < 8; ++corner) {
        const rt::vec3 q = rt::vec3(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y,
                                    corner & 4 ? box.hi.z : box.lo.z) - c;
        const rt::real z = glm::dot(q, axes.w);
        distance = std::max(distance, z + std::fabs(glm::dot(q, axes.u)) / tan_x);
        distance = std::max(distance, z + std::fabs(glm::dot(q, axes.v)) / tan_y);
    }
    cam.eye = c + axes.w * (distance * rt::real(1.05));
    cam.look_at = c;
    cam.fov_degrees = fov;
    return cam;
}

struct render_result {
    rt::image picture;
    std::vector<float> depth; // t per pixel (top row first), 0 where nothing is hit
    std::size_t hits = 0;
    double seconds = 0;     ///< wall clock
    double cpu_seconds = 0; ///< processor time
};

/// Traces one primary ray per pixel, one thread, and times the tracing.
render_result trace(const rt::accelerator& world, const rt::ray_generator& gen, bool geometric)
{
    render_result out;
    out.depth.assign(std::size_t(gen.nx) * std::size_t(gen.ny), 0.0f);
    std::vector<rt::vec3> normals(out.depth.size(), rt::vec3(0));
    const auto start = clock_type::now();
    const double cpu_start = cpu_seconds();
    for (int j = 0; j < gen.ny; ++j) {
        for (int i = 0; i < gen.nx; ++i) {
            const rt::ray r = rt::pixel_ray(gen, i, j);
            rt::hit_record rec;
            if (world.closest_hit(r, 0, rt::infinity, rec)) {
                const std::size_t at = std::size_t(gen.ny - 1 - j) * std::size_t(gen.nx) + std::size_t(i);
                out.depth[at] = float(rec.t * glm::length(r.direction));
                normals[at] = geometric ? rec.geometric_normal : rec.normal;
                ++out.hits;
            }
        }
    }
    out.seconds = seconds_since(start);
    out.cpu_seconds = cpu_seconds() - cpu_start;
    out.picture = rt::image(gen.nx, gen.ny);
    for (std::size_t k = 0; k < normals.size(); ++k)
        if (out.depth[k] > 0)
            out.picture.pixels[k] = rt::color((normals[k] + rt::vec3(1)) * rt::real(0.5));
    return out;
}

rt::image depth_image(const std::vector<float>& depth, int width, int height, bool raw)
{
    rt::image img(width, height);
    float nearest = std::numeric_limits<float>::infinity(), farthest = 0;
    for (float t : depth)
        if (t > 0) {
            nearest = std::min(nearest, t);
            farthest = std::max(farthest, t);
        }
    for (std::size_t k = 0; k < depth.size(); ++k) {
        if (!(depth[k] > 0))
            continue;
        if (raw) {
            img.pixels[k] = rt::color(depth[k]);
        } else {
            const float range = farthest > nearest ? farthest - nearest : 1.0f;
            img.pixels[k] = rt::color(1.0f - 0.8f * (depth[k] - nearest) / range); // near white, far grey
        }
    }
    return img;
}

// --- the crossover experiment --------------------------------------------------

/// n random triangles (or spheres) in the unit cube; `size` is their extent
/// times the cube root of n, so they fill the cube alike for every n.
rt::scene random_scene(std::size_t n, bool spheres, rt::real size, std::mt19937& random)
{
    std::uniform_real_distribution<rt::real> unit(0, 1);
    const rt::real extent = size / std::cbrt(rt::real(n));
    rt::scene s;
    for (std::size_t k = 0; k < n; ++k) {
        const rt::vec3 c(unit(random), unit(random), unit(random));
        if (spheres) {
            rt::sphere ball;
            ball.center = c;
            ball.radius = extent * rt::real(0.5);
            s.shapes.emplace_back(ball);
        } else {
            auto corner = [&] {
                return c + extent * (rt::vec3(unit(random), unit(random), unit(random)) - rt::real(0.5));
            };
            s.shapes.emplace_back(rt::triangle{corner(), corner(), corner(), -1});
        }
    }
    return s;
}

/// Nanoseconds of processor time per closest-hit query over `rays`, the best of a few runs.
double time_per_ray(const rt::accelerator& world, const std::vector<rt::ray>& rays, std::size_t& hits)
{
    double best = std::numeric_limits<double>::infinity();
    for (int run = 0; run < 5; ++run) {
        std::size_t count = 0;
        const double start = cpu_seconds();
        for (const rt::ray& r : rays) {
            rt::hit_record rec;
            count += world.closest_hit(r, 0, rt::infinity, rec) ? 1 : 0;
        }
        best = std::min(best, cpu_seconds() - start);
        hits = count;
    }
    return best * 1e9 / double(rays.size());
}

/// The experiment behind rt::flat_list_crossover: for n = 1 ... 256 random
/// triangles or spheres, small (most rays miss them) or large (most rays hit
/// one), the time per ray of the flat list and of the BVH.
int crossover()
{
    std::mt19937 random(2024);
    std::uniform_real_distribution<rt::real> unit(0, 1);
    std::vector<rt::ray> rays(20000);
    for (rt::ray& r : rays) { // from a point on a sphere around the cube to a point inside it
        const rt::real a = rt::real(6.2831853) * unit(random), z = 2 * unit(random) - 1;
        const rt::real ring = std::sqrt(1 - z * z);
        r.origin = rt::vec3(0.5) + rt::real(2) * rt::vec3(ring * std::cos(a), ring * std::sin(a), z);
        r.direction = rt::vec3(unit(random), unit(random), unit(random)) - r.origin;
    }
    const std::size_t counts[] = {1, 2, 3, 4, 5, 6, 7, 8, 10, 12, 16, 24, 32, 64, 128, 256};
    std::size_t wins_from = 0; // the smallest n from which the BVH wins in every column
    std::cout << "nanoseconds of processor time per closest-hit ray, one thread, " << rays.size()
              << " rays into the unit cube, best of 5 runs\n"
              << "           small primitives (most rays miss)    large primitives (most rays hit)\n"
              << "  n   triangles: flat    bvh  spheres: flat    bvh  triangles: flat    bvh  spheres: flat    bvh\n";
    for (std::size_t n : counts) {
        double ns[4][2] = {};
        bool bvh_wins = true;
        for (int column = 0; column < 4; ++column) {
            const bool spheres = column % 2 == 1;
            const rt::real size = column < 2 ? rt::real(0.5) : rt::real(2);
            const rt::scene s = random_scene(n, spheres, size, random);
            const rt::accelerator flat(s, rt::accelerator_kind::flat);
            const rt::accelerator tree(s, rt::accelerator_kind::bvh);
            std::size_t hits_flat = 0, hits_tree = 0;
            ns[column][0] = time_per_ray(flat, rays, hits_flat);
            ns[column][1] = time_per_ray(tree, rays, hits_tree);
            if (hits_flat != hits_tree)
                throw rt::error("the flat list and the BVH disagree on " + std::to_string(n) + " primitives");
            bvh_wins = bvh_wins && ns[column][1] < ns[column][0];
        }
        if (!bvh_wins)
            wins_from = 0;
        else if (wins_from == 0)
            wins_from = n;
        std::cout << std::setw(3) << n << std::fixed << std::setprecision(0);
        for (int column = 0; column < 4; ++column)
            std::cout << std::setw(column % 2 == 0 ? 18 : 15) << ns[column][0] << std::setw(7) << ns[column][1];
        std::cout << '\n';
    }
    std::cout << "the BVH is faster in every column from n = " << wins_from
              << "; rt::flat_list_crossover = " << rt::flat_list_crossover << '\n';
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage04_triangle", [&] {
        stage::arguments args(argc, argv);
        std::string input, output = "triangle.png", mode = "normals";
        int width = 0, height = 0, repeat = 1;
        rt::accelerator_kind kind = rt::accelerator_kind::automatic;
        rt::vec3 view(0, 0, 1);
        while (!args.done()) {
            const std::string arg = args.take();
            if (arg == "--help" || arg == "-h") {
                std::cout << usage;
                return 0;
            } else if (arg == "--crossover") {
                return crossover();
            } else if (arg == "-o") {
                output = args.value_of("-o");
            } else if (arg == "--mode") {
                mode = args.value_of("--mode");
                if (mode != "normals" && mode != "geometric" && mode != "depth")
                    throw rt::error("--mode: expected normals, geometric or depth, found '" + mode + "'");
            } else if (arg == "--size") {
                const std::string size = args.value_of("--size");
                const std::size_t x = size.find('x');
                if (x == std::string::npos)
                    throw rt::error("--size: expected WxH such as 800x600, found '" + size + "'");
                width = parse_int(size.substr(0, x), "--size width", 1, 16384);
                height = parse_int(size.substr(x + 1), "--size height", 1, 16384);
            } else if (arg == "--accel") {
                kind = rt::parse_accelerator_kind(args.value_of("--accel"));
            } else if (arg == "--view") {
                view.x = parse_real(args.value_of("--view"), "--view x");
                view.y = parse_real(args.value_of("--view"), "--view y");
                view.z = parse_real(args.value_of("--view"), "--view z");
                if (glm::dot(view, view) == 0)
                    throw rt::error("--view: expected a non-zero direction, found 0 0 0");
            } else if (arg == "--repeat") {
                repeat = parse_int(args.value_of("--repeat"), "--repeat", 1, 1000);
            } else if (!arg.empty() && arg[0] == '-') {
                throw rt::error("expected an option (-o, --mode, --size, --accel, --view, --repeat, --crossover, --help), found '" +
                                arg + "'; see --help");
            } else if (input.empty()) {
                input = arg;
            } else {
                throw rt::error("expected one input file, found also '" + arg + "'; see --help");
            }
        }
        if (input.empty())
            throw rt::error("expected an OBJ or scene file, found none; see --help");
        rt::check_image_output(output); // every option, the output format included, before any work
        stage::check_input_and_outputs(input, ends_with(input, ".scene") ? "a scene file" : "an OBJ file", {output});

        rt::scene world_scene;
        std::ostringstream load_summary; // printed once the outputs are checked against every file read
        const auto load_start = clock_type::now();
        if (ends_with(input, ".scene")) {
            world_scene = rt::load_scene(input);
            if (width == 0) {
                width = world_scene.width;
                height = world_scene.height;
            }
            std::size_t spheres = 0, triangles = 0, meshes = 0, mesh_triangles = 0, dropped = 0;
            for (const rt::shape& item : world_scene.shapes) {
                if (std::holds_alternative<rt::sphere>(item))
                    ++spheres;
                else if (std::holds_alternative<rt::triangle>(item))
                    ++triangles;
                else {
                    const rt::mesh& m = std::get<rt::mesh>(item);
                    ++meshes;
                    mesh_triangles += m.triangles.size();
                    dropped += m.dropped_degenerate;
                }
            }
            load_summary << input << ": " << spheres << " spheres, " << triangles << " triangles, " << meshes
                      << " meshes of " << mesh_triangles << " triangles (" << dropped
                      << " degenerate triangles dropped) (load " << std::setprecision(3) << seconds_since(load_start)
                      << " s)\n";
        } else {
            rt::obj_result loaded = rt::load_obj(input);
            load_summary << rt::summary(loaded) << " (load " << std::setprecision(3) << seconds_since(load_start)
                      << " s)\n";
            world_scene.materials = std::move(loaded.materials);
            world_scene.shapes.emplace_back(std::move(loaded.geometry));
            if (width == 0) {
                width = 800;
                height = 600;
            }
            world_scene.cam = frame_box(rt::scene_bounds(world_scene), view, width, height);
        }

        rt::check_not_input(output, rt::files_read(input, world_scene)); // its OBJ and MTL files too
        std::cout << load_summary.str();
        // the depth (4 bytes a pixel), the normals and the picture (12 each), and the image stored
        rt::check_memory_for(std::uint64_t(width) * std::uint64_t(height) * (4 + 12 + 12 + 12),
                             "a " + std::to_string(width) + "x" + std::to_string(height) + " image");
        const auto build_start = clock_type::now();
        const rt::accelerator world(world_scene, kind);
        const double build_seconds = seconds_since(build_start);
        const rt::bvh_stats& stats = world.stats();
        std::cout << std::fixed << std::setprecision(3) << "accelerator: " << rt::to_string(world.kind()) << " over "
                  << world.primitive_count() << " primitives, built in " << build_seconds << " s";
        if (world.kind() == rt::accelerator_kind::bvh)
            std::cout << "; " << stats.nodes << " 4-wide nodes (" << sizeof(rt::bvh_node) << " bytes each"
                      << (rt::bvh::uses_sse ? ", tested with SSE" : "") << "), "
                      << stats.leaves << " leaves, depth " << stats.depth << ", SAH cost " << std::setprecision(1)
                      << stats.sah_cost;
        std::cout << '\n';

        const rt::ray_generator gen = rt::make_ray_generator(world_scene.cam, width, height);
        render_result best = trace(world, gen, mode == "geometric");
        for (int k = 1; k < repeat; ++k) {
            render_result again = trace(world, gen, mode == "geometric");
            if (again.cpu_seconds < best.cpu_seconds)
                best = std::move(again);
        }
        const double rays = double(width) * double(height);
        std::cout << "traced " << width << "x" << height << " primary rays (" << std::setprecision(1)
                  << 100.0 * double(best.hits) / rays << "% hit), closest hit, 1 thread"
                  << (repeat > 1 ? ", fastest of " + std::to_string(repeat) : "") << ": " << std::setprecision(2)
                  << rays / best.cpu_seconds / 1e6 << " Mrays/s of processor time (" << std::setprecision(4)
                  << best.cpu_seconds << " s; wall clock " << best.seconds << " s)\n";

        const bool pfm = ends_with(output, ".pfm");
        const rt::image result = mode == "depth" ? depth_image(best.depth, width, height, pfm) : best.picture;
        rt::save_image(output, result, 1.0f);
        std::cout << "wrote " << output << " (" << mode << ")\n";
        return 0;
    });
}
