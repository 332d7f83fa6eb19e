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
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <iostream>
#include <optional>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include <rt/camera/camera.hpp>
#include <rt/core/hit_record.hpp>
#include <rt/core/image.hpp>
#include <rt/system/atomic_file.hpp>
#include <rt/scene/scene.hpp>
#include <rt/intersection/sphere.hpp>
#include <rt/intersection/sphere_stable.hpp>

#include "pixel_story.hpp"
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

/// The spheres through the loop of closest_sphere_hit, as an accelerator for
/// the pixel's story; every sphere that the ray hits is written to
/// `candidates` in loop order.
struct sphere_list {
    const std::vector<rt::sphere>* spheres;
    const std::vector<std::uint32_t>* shape_index;
    bool (*hit)(const rt::sphere&, const rt::ray&, rt::real, rt::real, rt::hit_record&);
    std::vector<std::string>* candidates;

    bool closest_hit(const rt::ray& r, rt::real tmin, rt::real tmax, rt::hit_record& closest) const
    {
        bool found = false;
        for (std::size_t k = 0; k < spheres->size(); ++k) {
            rt::hit_record rec;
            if (hit((*spheres)[k], r, tmin, tmax, rec)) {
                found = true;
                tmax = rec.t;
                closest = rec;
                closest.shape = (*shape_index)[k];
                candidates->push_back("shape " + std::to_string(closest.shape) + " at t " + std::to_string(rec.t) +
                                      " (nearest so far)");
            }
        }
        return found;
    }
    bool any_hit(const rt::ray& r, rt::real tmin, rt::real tmax) const
    {
        rt::hit_record unused;
        return closest_hit(r, tmin, tmax, unused);
    }
};

using hit_function = bool (*)(const rt::sphere&, const rt::ray&, rt::real, rt::real, rt::hit_record&);

/// The nearest hit of the ray with any of the spheres, in [0, infinity).
bool closest_sphere_hit(const std::vector<rt::sphere>& spheres, const std::vector<std::uint32_t>& shape_index,
                        hit_function hit, const rt::ray& r, rt::hit_record& closest)
{
    bool found = false;
    rt::real tmax = std::numeric_limits<rt::real>::infinity();
    for (std::size_t k = 0; k < spheres.size(); ++k) {
        rt::hit_record rec;
        if (hit(spheres[k], r, 0, tmax, rec)) {
            found = true;
            tmax = rec.t; // from now on only nearer hits count
            closest = rec;
            closest.shape = shape_index[k];
        }
    }
    return found;
}

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage03_sphere", [&] {
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
        const std::string hit_png = prefix + "-hit.png", normal_png = prefix + "-normal.png",
                          normal_pfm = prefix + "-normal.pfm", depth_pfm = prefix + "-depth.pfm",
                          depth_png = prefix + "-depth.png";
        std::vector<std::filesystem::path> outputs;
        for (const std::string& name : {hit_png, normal_png, normal_pfm, depth_pfm, depth_png})
            outputs.push_back(stage::file_argument(name));
        if (!pixel.wanted) {
            for (const std::filesystem::path& output : outputs)
                rt::check_writable(output); // fail before the work, not after it
            stage::check_input_and_outputs(scene_path, "a scene file", outputs);
        }

        const rt::scene s = stage::load_scene(scene_path);
        if (!pixel.wanted) {
            rt::check_not_input(outputs, rt::files_read(stage::file_argument(scene_path), s)); // its OBJ and MTL files too
            // five images of 12 bytes a pixel (three floats), and the PNGs' bytes
            rt::check_memory_for(std::uint64_t(s.width) * std::uint64_t(s.height) * (5 * 12 + 3),
                                 "five " + std::to_string(s.width) + "x" + std::to_string(s.height) + " images");
        }
        std::vector<rt::sphere> spheres;
        std::vector<std::uint32_t> shape_index;
        std::size_t skipped_triangles = 0, skipped_meshes = 0;
        for (std::size_t k = 0; k < s.shapes.size(); ++k) {
            if (const rt::sphere* ball = std::get_if<rt::sphere>(&s.shapes[k])) {
                spheres.push_back(*ball);
                shape_index.push_back(std::uint32_t(k));
            } else if (std::holds_alternative<rt::triangle>(s.shapes[k])) {
                ++skipped_triangles;
            } else {
                ++skipped_meshes;
            }
        }
        const hit_function hit = method == "stable" ? hit_function(rt::hit_sphere) : hit_function(rt::hit_sphere_textbook);

        const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
        if (pixel.wanted) {
            stage::story st;
            st.program = "stage03_sphere";
            stage::place_pixel(st, pixel.column, pixel.row, gen.nx, gen.ny);
            st.camera = rt::pixel_ray(gen, st.i, st.j);
            std::vector<std::string> candidates;
            const sphere_list list{&spheres, &shape_index, hit, &candidates};
            rt::hit_record rec;
            const bool found = stage::recording<sphere_list>(list, st.queries)
                                   .closest_hit(st.camera, 0, std::numeric_limits<rt::real>::infinity(), rec);
            stage::name_queries(st);
            std::string order;
            for (const std::string& line : candidates)
                order += (order.empty() ? "" : "; ") + line;
            st.values.push_back({"spheres hit in loop order:", order.empty() ? "none" : order});
            st.values.push_back({"method:", method});
            if (found) {
                const rt::color n(rec.normal);
                const rt::color shown = (n + rt::color(1)) * 0.5f;
                st.linear = shown;
                st.values.push_back({"hit image:", "white"});
                st.values.push_back({"normal image (n + 1) / 2:", std::to_string(shown.r) + " " + std::to_string(shown.g) +
                                                                     " " + std::to_string(shown.b)});
                st.values.push_back({"depth t |d|:", std::to_string(rec.t * glm::length(st.camera.direction))});
            } else {
                st.values.push_back({"hit image:", "black (a miss)"});
            }
            if (pixel.json)
                stage::print_story_json(std::cout, st, s);
            else
                stage::print_story(std::cout, st, s);
            return 0;
        }
        rt::image hits(s.width, s.height), normals(s.width, s.height), normal_values(s.width, s.height),
            depths(s.width, s.height);
        float nearest = std::numeric_limits<float>::infinity(), farthest = 0;
        std::size_t hit_count = 0;
        for (int j = 0; j < gen.ny; ++j)
            for (int i = 0; i < gen.nx; ++i) {
                const rt::ray r = rt::pixel_ray(gen, i, j);
                rt::hit_record rec;
                if (!closest_sphere_hit(spheres, shape_index, hit, r, rec))
                    continue; // every buffer is 0 (black) where the ray missed
                const int row = gen.ny - 1 - j; // images store the top row first
                const rt::color n(rec.normal);
                const float depth = float(rec.t * glm::length(r.direction));
                hits.at(i, row) = rt::color(1);
                normals.at(i, row) = (n + rt::color(1)) * 0.5f;
                normal_values.at(i, row) = n;
                depths.at(i, row) = rt::color(depth);
                nearest = std::min(nearest, depth);
                farthest = std::max(farthest, depth);
                ++hit_count;
            }
        rt::image depth_view(s.width, s.height); // misses stay black, distinct from the farthest hit
        const float range = farthest - nearest;
        for (std::size_t k = 0; k < depths.pixels.size(); ++k)
            if (depths.pixels[k].r > 0)
                depth_view.pixels[k] =
                    rt::color(range > 0 ? 1.0f - 0.75f * (depths.pixels[k].r - nearest) / range : 1.0f);

        // all five or none: every file is complete before the first replaces its target
        stage::save_images({{hit_png, &hits, 1.0f}, {normal_png, &normals, 1.0f}, {normal_pfm, &normal_values, 1.0f},
                            {depth_pfm, &depths, 1.0f}, {depth_png, &depth_view, 1.0f}});

        std::cerr << "stage03_sphere: " << spheres.size() << " sphere(s) intersected with the " << method << " method";
        if (skipped_triangles + skipped_meshes > 0)
            std::cerr << "; skipped " << skipped_triangles << " triangle(s) and " << skipped_meshes
                      << " mesh(es) (stage 04)";
        std::cerr << "\n" << hit_count << " of " << std::size_t(s.width) * std::size_t(s.height) << " rays hit";
        if (hit_count > 0)
            std::cerr << ", depth " << nearest << " to " << farthest;
        std::cerr << "\nwrote " << hit_png << ", " << normal_png << ", " << normal_pfm << ", " << depth_pfm << ", "
                  << depth_png << "\n";
        return 0;
    });
}
