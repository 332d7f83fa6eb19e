// triangle_pass.hpp - what stage 04's program does with a scene: one ray per
// pixel through an accelerator (the student's list or groups, or the library's
// BVH), timed; the picture of the hits; where two sets of hits differ; and the
// story of one pixel through the student's list.
//
//     const stage::timed_hits mine = stage::trace_timed(groups, "your groups", gen, false);
//     stage::save_image("out.png", stage::picture_of(mine.hits, gen.nx, gen.ny, "normals", false), 1.0f);
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include <rt/camera/camera.hpp>
#include <rt/core/error.hpp>
#include <rt/core/hit_record.hpp>
#include <rt/core/image.hpp>
#include <rt/scene/scene.hpp>
#include <rt/system/parallel.hpp>

#include "pixel_story.hpp"
#include "stage_main.hpp"
#include "support.hpp"
#include "textbook_groups.hpp"
#include "textbook_list.hpp"

namespace stage {

using clock_type = std::chrono::steady_clock;

inline double seconds_since(clock_type::time_point start)
{
    return std::chrono::duration<double>(clock_type::now() - start).count();
}

/// "INPUT: 3 sphere(s), 2 triangle(s), 1 mesh(es) of 12 triangle(s) (load T s)" on stdout.
inline void print_shape_counts(const std::string& input, const shape_counts& n, double load_seconds)
{
    std::cout << input << ": " << n.spheres << " sphere(s), " << n.triangles << " triangle(s), " << n.meshes
              << " mesh(es) of " << n.mesh_triangles << " triangle(s) (load " << std::setprecision(3)
              << load_seconds << " s)\n";
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

/// The hits of a trace and how fast it went.
struct timed_hits {
    std::vector<pixel_hit> hits;
    double rate = 0; ///< rays a second
};

/// The pixels traced with `world` (every row_step-th row), timed, and one line on
/// stdout: how many hit, how fast.
template <class Accelerator>
timed_hits trace_timed(const Accelerator& world, const std::string& name, const rt::ray_generator& gen,
                       bool geometric, int row_step = 1)
{
    const auto start = clock_type::now();
    timed_hits out{trace_image(world, gen, geometric, row_step), 0};
    const double seconds = seconds_since(start);
    const std::size_t rays = std::size_t((gen.ny + row_step - 1) / row_step) * std::size_t(gen.nx);
    std::size_t count = 0;
    for (const pixel_hit& h : out.hits)
        count += h.hit ? 1 : 0;
    out.rate = double(rays) / std::max(seconds, 1e-9);
    std::cout << name << ": " << count << " of " << rays << " rays hit, " << std::setprecision(3) << seconds
              << " s (" << out.rate / 1e6 << " Mrays/s)\n";
    return out;
}

/// The student's groups (build_groups, closest_hit_groups), timed; then the
/// student's list, timed on one row in `step` when the whole image would take
/// it more than 1e8 tests (a few seconds), and the groups' speed-up over it.
inline std::vector<pixel_hit> trace_groups_and_list(const rt::scene& s, const rt::ray_generator& gen, bool geometric,
                                                    std::size_t primitives)
{
    const auto build_start = clock_type::now();
    const textbook_groups groups(s);
    std::ostringstream name;
    name << "your groups (" << groups.g.items.size() << " items, " << groups.g.nodes.size() << " nodes, built in "
         << std::setprecision(3) << seconds_since(build_start) << " s)";
    timed_hits mine = trace_timed(groups, name.str(), gen, geometric);
    const double tests = double(primitives) * double(gen.nx) * double(gen.ny);
    const int step = int(std::min(double(gen.ny), std::max(1.0, std::ceil(tests / 1e8))));
    const std::string list_name =
        step == 1 ? std::string("your list") : "your list (one row in " + std::to_string(step) + ")";
    const double list_rate = trace_timed(textbook_list{&s}, list_name, gen, geometric, step).rate;
    std::ostringstream speed_up;
    speed_up << std::fixed << std::setprecision(1) << mine.rate / list_rate;
    std::cout << "your groups' speed-up over your list: " << speed_up.str() << "x\n";
    return std::move(mine.hits);
}

/// The library's accelerator of `kind` (flat, bvh or auto), built and timed.
inline std::vector<pixel_hit> trace_library(const rt::scene& s, const rt::ray_generator& gen, bool geometric,
                                            const std::string& kind)
{
    const auto build_start = clock_type::now();
    const world library(s, kind);
    std::ostringstream name;
    name << "the library (" << library.kind() << " over " << library.primitives() << " primitives";
    if (library.kind() == "bvh")
        name << ", " << library.nodes() << " nodes";
    name << ", built in " << std::setprecision(3) << seconds_since(build_start) << " s)";
    return trace_timed(library, name.str(), gen, geometric).hits;
}

/// The image of the hits: (n + 1) / 2 of the normal, or the depth (itself when
/// `raw`, for a PFM; else near white, far grey); black where the ray missed.
inline rt::image picture_of(const std::vector<pixel_hit>& hits, int width, int height, const std::string& mode,
                            bool raw)
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
        else // near white, far grey
            img.pixels[k] =
                rt::color(1.0f - 0.8f * (hits[k].depth - nearest) / (farthest > nearest ? farthest - nearest : 1.0f));
    }
    return img;
}

/// Where the student's hits and the library's differ, with one line on stdout:
/// red where only the library hits (a ray that leaked through the student's
/// triangles), blue where only the student's does, yellow where both hit other
/// shapes or depths, grey where they agree.
inline rt::image difference(const std::vector<pixel_hit>& mine, const std::vector<pixel_hit>& library, int width,
                            int height, const std::string& yours)
{
    rt::image diff(width, height);
    std::size_t leaks = 0, extra = 0, other = 0;
    for (std::size_t k = 0; k < mine.size(); ++k) {
        const pixel_hit& a = mine[k];
        const pixel_hit& b = library[k];
        if (b.hit && !a.hit) {
            ++leaks;
            diff.pixels[k] = rt::color(1, 0, 0);
        } else if (a.hit && !b.hit) {
            ++extra;
            diff.pixels[k] = rt::color(0, 0, 1);
        } else if (a.hit && (a.shape != b.shape || std::fabs(a.depth - b.depth) > 1e-4f * std::max(a.depth, b.depth))) {
            ++other;
            diff.pixels[k] = rt::color(1, 1, 0);
        } else if (a.hit) {
            diff.pixels[k] = rt::color(0.25f); // the same hit
        }
    }
    std::cout << yours << " against the library's: " << leaks + extra + other << " of " << mine.size()
              << " pixels differ (" << leaks << " leaked through your triangles: the library hits, yours "
              << "misses; " << extra << " hit only with yours; " << other << " hit a different shape or depth)\n";
    return diff;
}

/// The list tests every shape for every ray: about 10 ns a test, so beyond a
/// few billion tests it would take minutes (the bunny at 640x480: 21 billion).
inline void check_list_is_quick_enough(std::size_t primitives, int width, int height)
{
    const double tests = double(primitives) * double(width) * double(height);
    if (tests > 3e9)
        throw rt::error("expected a scene the list can trace in a minute, found " + std::to_string(primitives) +
                        " shapes for each of " + std::to_string(width * height) + " rays (" +
                        std::to_string(tests / 1e9).substr(0, 5) +
                        " billion tests); try --size 160x120, --accel groups for your groups, or --accel bvh "
                        "for the library's BVH");
}

/// --pixel I J: the camera ray through the student's list, and what the
/// library's BVH finds for the same ray, printed to stdout.
inline void tell_triangle_story(const rt::scene& s, const rt::ray_generator& gen, const pixel_request& pixel)
{
    story st;
    st.program = "stage04_triangle";
    place_pixel(st, pixel.column, pixel.row, gen.nx, gen.ny);
    st.camera = rt::pixel_ray(gen, st.i, st.j);
    const textbook_list list{&s};
    rt::hit_record rec;
    recording<textbook_list>(list, st.queries).closest_hit(st.camera, 0, rt::infinity, rec);
    name_queries(st);
    st.values.push_back({"method:", "your closest_hit_list with hit_triangle_moller_trumbore and hit_sphere_textbook"});
    const world library(s, "auto");
    rt::hit_record reference;
    const bool library_hit = library.closest_hit(st.camera, 0, rt::infinity, reference);
    st.values.push_back({"the library's BVH:", library_hit ? "hits shape " + std::to_string(reference.shape) +
                                                                 " at t " + std::to_string(reference.t)
                                                           : std::string("misses")});
    if (!st.queries.empty() && st.queries[0].hit)
        st.linear = rt::color((st.queries[0].rec.normal + rt::vec3(1)) * rt::real(0.5));
    if (pixel.json)
        print_story_json(std::cout, st, s);
    else
        print_story(std::cout, st, s);
}

} // namespace stage
