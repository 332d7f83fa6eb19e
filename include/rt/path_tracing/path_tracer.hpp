// path_tracer.hpp - the path tracer that stage 11's exercises make (stage 11).
//
// Kajiya's path tracing (J. T. Kajiya, "The Rendering Equation", SIGGRAPH
// 1986), in the form of PBR 4th ed., sec. 13.3-13.4: a camera ray, then at
// each surface one random direction onward, carrying the throughput (the
// product of the BSDF weights so far). At each point a path gathers
//   - the emission Le of the surface it meets, weighted (mis.hpp);
//   - with next-event estimation, the light of a random emitter point behind
//     a shadow ray (next_event.hpp), weighted;
// then draws its next direction (lambertian.hpp; uniform over the hemisphere
// for the `uniform` strategy), and after a few bounces plays Russian roulette
// (roulette.hpp). A path that leaves the scene gains the background: the
// radiance of a uniform environment. Every surface is Lambertian with albedo
// kd (a material's mirror, glass and highlight terms are left to stages 07-10).
//
// render_paths draws each pixel's samples from generators seeded by (seed,
// pixel, sample) (random.hpp), so the image is the same for any thread count;
// with adaptive sampling (adaptive.hpp) a pixel stops after the batch whose
// confidence interval is narrow enough.
//
//     const rt::accelerator accel(s);
//     const rt::emitter_list lights = rt::find_emitters(s);
//     rt::pcg32 rng = ...;
//     rt::color L = rt::path_radiance(s, accel, lights, camera_ray, rng, options);
//
// A program that wants to know what the path did passes an observer
// (path_observer.hpp): rt::path_story_recorder{&story} writes it down for
// stage 11's --pixel, rt::ray_count_observer{&rays} counts its rays.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include <glm/geometric.hpp>

#include "adaptive.hpp"
#include "../core/config.hpp"
#include "emitters.hpp"
#include "hemisphere.hpp"
#include "../core/hit_record.hpp"
#include "../core/image.hpp"
#include "lambertian.hpp"
#include "../scene/material.hpp"
#include "mis.hpp"
#include "next_event.hpp"
#include "path_observer.hpp"
#include "path_story.hpp"
#include "../system/parallel.hpp"
#include "../core/random.hpp"
#include "../core/ray.hpp"
#include "../rendering/renderer.hpp" // integrator_stream
#include "roulette.hpp"
#include "../scene/scene.hpp"
#include "../intersection/spawn.hpp"
#include "../core/vec.hpp"

namespace rt {

struct path_options {
    path_strategy strategy = path_strategy::mis;
    int max_bounces = 64;            ///< a path ends after this many bounces whatever the roulette says
    bool roulette = true;            ///< Russian roulette from roulette_start bounces on
    int roulette_start = rt::roulette_start;
};

/// The radiance the path of `camera_ray` brings back (see the top of this
/// file), with random numbers from `rng`. `observe` hears each step of the
/// path (path_observer.hpp: the story of stage 11's --pixel, a count of rays);
/// the default hears nothing.
template <class Accelerator, class Observer = no_path_observer,
          class = std::enable_if_t<!std::is_pointer_v<std::decay_t<Observer>> &&
                                   !std::is_null_pointer_v<std::decay_t<Observer>>>>
color path_radiance(const scene& s, const Accelerator& accel, const emitter_list& lights, const ray& camera_ray,
                    pcg32& rng, const path_options& o, Observer&& observe = Observer{})
{
    const real infinite = std::numeric_limits<real>::infinity();
    const bool aim = samples_lights(o.strategy) && !lights.empty();
    color L(0.0f), throughput(1.0f);
    ray r = camera_ray;
    real pdf_before = 0;     // the density of the direction that led here
    std::uint64_t rays = 0; // traced after the camera ray, told at the end
    for (int bounce = 0;; ++bounce) {
        hit_record hit;
        if (bounce > 0)
            ++rays;
        if (!accel.closest_hit(r, 0, infinite, hit)) {
            const color background = throughput * s.background;
            L += background;
            observe.end(path_end::escaped, background, L, rays);
            return L;
        }
        observe.surface(hit, throughput);
        const material& m = s.material_of(hit.material);
        color added(0.0f);
        // the emission Le of the surface, weighted against next-event estimation's
        // chance of having found it (mis.hpp)
        const color glow = emitted_radiance(s, hit, r.direction);
        if (glow != color(0.0f)) {
            const bool sampled = hit_sampled_emitter(s, hit);
            real pdf_light = 0;
            if (bounce > 0 && sampled && aim) {
                const real d = hit.t * glm::length(r.direction);
                const real cos_y = glm::dot(hit.geometric_normal, glm::normalize(r.direction));
                pdf_light = solid_angle_pdf(real(1 / lights.total_area), d, cos_y);
            }
            const real weight = emission_weight(o.strategy, bounce, sampled, pdf_before, pdf_light);
            observe.emission(glow, weight);
            added += throughput * glow * float(weight);
        }
        // next-event estimation: a random point y of the emitters, behind a shadow ray
        const vec3 n = hit.normal; // faces the ray: the side the path is on
        const bool last = bounce >= o.max_bounces;
        if (!last && aim) {
            const real xi0 = rng.next_float(), xi1 = rng.next_float(), xi2 = rng.next_float();
            const emitter_sample y = sample_emitters(lights, xi0, xi1, xi2);
            const color estimate = next_event_estimate(m.kd, hit.point, n, y);
            bool visible = false;
            real weight = 0;
            if (estimate != color(0.0f)) {
                ++rays;
                visible = !accel.any_hit(spawn_ray_to(hit, y.point), 0, 1 - shadow_epsilon);
                if (visible) {
                    const vec3 to_light = y.point - hit.point;
                    const real d = glm::length(to_light);
                    const vec3 w = to_light / d;
                    const real pdf_light = solid_angle_pdf(y.pdf_area, d, glm::dot(y.normal, w));
                    weight = light_sample_weight(o.strategy, pdf_light, cosine_hemisphere_pdf(glm::dot(n, w)));
                    added += throughput * estimate * float(weight);
                }
            }
            observe.light(y, estimate, visible, weight);
        }
        observe.added(added);
        L += added;
        if (last) {
            observe.end(path_end::max_bounces, color(0.0f), L, rays);
            return L;
        }
        // the next direction, and the throughput it carries on
        const real xi1 = rng.next_float(), xi2 = rng.next_float();
        bsdf_sample next;
        if (o.strategy == path_strategy::uniform) {
            const vec3 local = uniform_hemisphere(xi1, xi2);
            next.direction = to_world(local, n);
            next.pdf = uniform_hemisphere_pdf();
            next.weight = lambertian_brdf(m.kd) * float(local.z / next.pdf);
        } else {
            next = sample_lambertian(m.kd, n, xi1, xi2);
        }
        observe.bounce(next);
        throughput *= next.weight;
        pdf_before = next.pdf;
        if (!(next.pdf > 0) || throughput == color(0.0f)) { // a NaN density ends it too
            observe.end(path_end::absorbed, color(0.0f), L, rays);
            return L;
        }
        if (o.roulette && bounce + 1 >= o.roulette_start) {
            const real xi = rng.next_float();
            const bool survived = russian_roulette(throughput, bounce + 1, o.roulette_start, xi);
            observe.roulette(survived);
            if (!survived) {
                observe.end(path_end::roulette, color(0.0f), L, rays);
                return L;
            }
        }
        r = spawn_ray(hit, next.direction);
    }
}

/// The form before observers (0.1): `story` and `rays` may each be null.
template <class Accelerator>
[[deprecated("use path_radiance(..., o, rt::path_story_recorder{&story}) or rt::ray_count_observer{&rays}")]]
color path_radiance(const scene& s, const Accelerator& accel, const emitter_list& lights, const ray& camera_ray,
                    pcg32& rng, const path_options& o, path_story* story, std::uint64_t* rays = nullptr)
{
    path_story ignored;
    struct both : path_story_recorder {
        std::uint64_t* count;
        both(path_story* into, std::uint64_t* counter) : path_story_recorder(into), count(counter) {}
        void end(path_end why, const color& background_added, const color& radiance, std::uint64_t rays)
        {
            path_story_recorder::end(why, background_added, radiance, rays);
            if (count)
                *count += rays;
        }
    } observe(story ? story : &ignored, rays);
    return path_radiance(s, accel, lights, camera_ray, rng, o, observe);
}

struct path_render_options {
    int width = 64, height = 64;
    int samples_per_pixel = 16;   ///< per pixel; with adaptive sampling, the most a pixel takes
    std::uint64_t seed = 0;
    int threads = 0;              ///< 0: every hardware thread
    path_options path;
    bool adaptive = false;        ///< stop a pixel when its confidence interval is narrow (adaptive.hpp)
    int batch = 32;               ///< adaptive: samples between two tests
    double max_tolerance = 0.05;  ///< adaptive: I <= max_tolerance mu
};

struct path_render_result {
    image pixels;
    std::vector<int> samples;     ///< per pixel, top row first
    std::uint64_t rays = 0;       ///< every ray traced, camera rays included
    double seconds = 0;
};

/// The image of `s` by path tracing: ray_at(x, y) gives the camera ray
/// through the film position (x, y) (pixels from the bottom-left corner, as
/// rt::generate_ray takes them); each pixel averages its samples (a box
/// filter), each sample at a uniform random position in the pixel.
template <class Accelerator, class RaySource>
path_render_result render_paths(const scene& s, const Accelerator& accel, const emitter_list& lights,
                                const RaySource& ray_at, const path_render_options& o)
{
    const auto start = std::chrono::steady_clock::now();
    path_render_result out;
    out.pixels = image(o.width, o.height);
    out.samples.assign(std::size_t(o.width) * std::size_t(o.height), 0);
    std::vector<std::uint64_t> row_rays(std::size_t(o.height), 0);
    const int batch = o.batch > 0 ? o.batch : 1;
    parallel_for(std::size_t(o.height), thread_count(o.threads), [&](std::size_t row, int) {
        const int y = int(row);
        std::uint64_t traced = 0;
        for (int x = 0; x < o.width; ++x) {
            const std::uint64_t pixel = std::uint64_t(y) * std::uint64_t(o.width) + std::uint64_t(x);
            double sum_r = 0, sum_g = 0, sum_b = 0;
            pixel_statistics stats;
            for (int k = 0; k < o.samples_per_pixel; ++k) {
                pcg32 rng = seeded_generator(o.seed, pixel, std::uint64_t(k) + 1, integrator_stream);
                const real fx = rng.next_float(), fy = rng.next_float();
                const ray r = ray_at(real(x) + fx, real(o.height - 1 - y) + fy);
                const color L = path_radiance(s, accel, lights, r, rng, o.path, ray_count_observer{&traced});
                ++traced;
                sum_r += double(L.r);
                sum_g += double(L.g);
                sum_b += double(L.b);
                stats.add(luminance(L));
                if (o.adaptive && stats.n % batch == 0 && pixel_converged(stats, o.max_tolerance))
                    break;
            }
            const double n = stats.n > 0 ? double(stats.n) : 1;
            out.pixels.at(x, y) = color(float(sum_r / n), float(sum_g / n), float(sum_b / n));
            out.samples[std::size_t(pixel)] = stats.n;
        }
        row_rays[row] = traced;
    });
    for (const std::uint64_t n : row_rays)
        out.rays += n;
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace rt
