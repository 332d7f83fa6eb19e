// sphere_pass.hpp - what stage 03's program does with the scene's spheres: one
// ray per pixel, the nearest hit by a flat loop (the course's "closest hit":
// each hit narrows tmax), the five images made from the hits, and the story of
// one pixel told by the same loop.
//
//     const stage::sphere_set set = stage::spheres_of(s);
//     const stage::sphere_images out = stage::trace_spheres(set, rt::hit_sphere_textbook, gen);
//
// Triangles and meshes are stage 04's: spheres_of counts them and leaves them out.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iostream>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include <glm/geometric.hpp>

#include <rt/camera/camera.hpp>
#include <rt/core/hit_record.hpp>
#include <rt/core/image.hpp>
#include <rt/intersection/sphere.hpp>
#include <rt/scene/scene.hpp>

#include "pixel_story.hpp"
#include "stage_main.hpp"

namespace stage {

/// A sphere test: the student's hit_sphere_textbook or the library's hit_sphere.
using sphere_hit_function = bool (*)(const rt::sphere&, const rt::ray&, rt::real, rt::real, rt::hit_record&);

/// The scene's spheres, each with its index among the scene's shapes, and what was left out.
struct sphere_set {
    std::vector<rt::sphere> spheres;
    std::vector<std::uint32_t> shape_index;
    std::size_t skipped_triangles = 0, skipped_meshes = 0;
};

inline sphere_set spheres_of(const rt::scene& s)
{
    sphere_set set;
    for (std::size_t k = 0; k < s.shapes.size(); ++k) {
        if (const rt::sphere* ball = std::get_if<rt::sphere>(&s.shapes[k])) {
            set.spheres.push_back(*ball);
            set.shape_index.push_back(std::uint32_t(k));
        } else if (std::holds_alternative<rt::triangle>(s.shapes[k])) {
            ++set.skipped_triangles;
        } else {
            ++set.skipped_meshes;
        }
    }
    return set;
}

/// The nearest hit in [tmin, tmax] of the ray with any of the spheres, in loop
/// order; on_hit(rec) sees each hit that narrowed tmax (the pixel's story lists them).
template <class OnHit>
bool closest_sphere_hit(const sphere_set& set, sphere_hit_function hit, const rt::ray& r, rt::real tmin,
                        rt::real tmax, rt::hit_record& closest, OnHit&& on_hit)
{
    bool found = false;
    for (std::size_t k = 0; k < set.spheres.size(); ++k) {
        rt::hit_record rec;
        if (hit(set.spheres[k], r, tmin, tmax, rec)) {
            found = true;
            tmax = rec.t; // from now on only nearer hits count
            closest = rec;
            closest.shape = set.shape_index[k];
            on_hit(closest);
        }
    }
    return found;
}

/// The five pictures of stage 03 (rows top first; 0, black, where a ray missed).
struct sphere_images {
    rt::image hits, normals, normal_values, depths, depth_view;
    float nearest = std::numeric_limits<float>::infinity(), farthest = 0;
    std::size_t hit_count = 0;
};

/// One ray per pixel through the loop, in [0, infinity): white where it hit, the
/// normal n as (n + 1) / 2 and as itself, the depth t |d| as itself and as grey
/// from the nearest hit (white) to the farthest (a quarter grey).
inline sphere_images trace_spheres(const sphere_set& set, sphere_hit_function hit, const rt::ray_generator& gen)
{
    sphere_images out{rt::image(gen.nx, gen.ny), rt::image(gen.nx, gen.ny), rt::image(gen.nx, gen.ny),
                      rt::image(gen.nx, gen.ny), rt::image(gen.nx, gen.ny)};
    for (int j = 0; j < gen.ny; ++j)
        for (int i = 0; i < gen.nx; ++i) {
            const rt::ray r = rt::pixel_ray(gen, i, j);
            rt::hit_record rec;
            if (!closest_sphere_hit(set, hit, r, 0, std::numeric_limits<rt::real>::infinity(), rec,
                                    [](const rt::hit_record&) {}))
                continue;
            const int row = gen.ny - 1 - j; // images store the top row first
            const rt::color n(rec.normal);
            const float depth = float(rec.t * glm::length(r.direction));
            out.hits.at(i, row) = rt::color(1);
            out.normals.at(i, row) = (n + rt::color(1)) * 0.5f;
            out.normal_values.at(i, row) = n;
            out.depths.at(i, row) = rt::color(depth);
            out.nearest = std::min(out.nearest, depth);
            out.farthest = std::max(out.farthest, depth);
            ++out.hit_count;
        }
    const float range = out.farthest - out.nearest; // misses stay black, distinct from the farthest hit
    for (std::size_t k = 0; k < out.depths.pixels.size(); ++k)
        if (out.depths.pixels[k].r > 0)
            out.depth_view.pixels[k] =
                rt::color(range > 0 ? 1.0f - 0.75f * (out.depths.pixels[k].r - out.nearest) / range : 1.0f);
    return out;
}

/// The loop as an accelerator, so that the story's `recording` can ask it.
struct sphere_loop {
    const sphere_set* set;
    sphere_hit_function hit;
    std::vector<std::string>* candidates; ///< every hit that narrowed tmax, in loop order

    bool closest_hit(const rt::ray& r, rt::real tmin, rt::real tmax, rt::hit_record& closest) const
    {
        return closest_sphere_hit(*set, hit, r, tmin, tmax, closest, [&](const rt::hit_record& rec) {
            candidates->push_back("shape " + std::to_string(rec.shape) + " at t " + std::to_string(rec.t) +
                                  " (nearest so far)");
        });
    }
    bool any_hit(const rt::ray& r, rt::real tmin, rt::real tmax) const
    {
        rt::hit_record unused;
        return closest_hit(r, tmin, tmax, unused);
    }
};

/// --pixel I J: the camera ray of the pixel, every sphere it hits in loop order,
/// the nearest hit and the values the images hold there, printed to stdout.
inline void tell_sphere_story(const rt::scene& s, const sphere_set& set, sphere_hit_function hit,
                              const std::string& method, const rt::ray_generator& gen, const pixel_request& pixel)
{
    story st;
    st.program = "stage03_sphere";
    place_pixel(st, pixel.column, pixel.row, gen.nx, gen.ny);
    st.camera = rt::pixel_ray(gen, st.i, st.j);
    std::vector<std::string> candidates;
    const sphere_loop loop{&set, hit, &candidates};
    rt::hit_record rec;
    const bool found = recording<sphere_loop>(loop, st.queries)
                           .closest_hit(st.camera, 0, std::numeric_limits<rt::real>::infinity(), rec);
    name_queries(st);
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
        st.values.push_back({"normal image (n + 1) / 2:",
                             std::to_string(shown.r) + " " + std::to_string(shown.g) + " " + std::to_string(shown.b)});
        st.values.push_back({"depth t |d|:", std::to_string(rec.t * glm::length(st.camera.direction))});
    } else {
        st.values.push_back({"hit image:", "black (a miss)"});
    }
    if (pixel.json)
        print_story_json(std::cout, st, s);
    else
        print_story(std::cout, st, s);
}

} // namespace stage
