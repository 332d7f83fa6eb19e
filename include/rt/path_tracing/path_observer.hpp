// path_observer.hpp - what rt::path_radiance tells an observer as a path goes
// (stage 11), so that the estimator's loop holds the estimator alone: a
// program that wants the story of a path (stage 11's --pixel) or a count of
// its rays passes an observer; the default hears nothing and costs nothing.
//
//     rt::path_story story;
//     rt::path_radiance(s, accel, lights, camera_ray, rng, options, rt::path_story_recorder{&story});
//     std::uint64_t rays = 0;
//     rt::path_radiance(s, accel, lights, camera_ray, rng, options, rt::ray_count_observer{&rays});
//
// An observer of one's own derives from rt::no_path_observer and hides the
// calls it wants (they are found by name, at compile time: no virtual call).
#pragma once

#include <cstdint>

#include "../core/config.hpp"
#include "../core/hit_record.hpp"
#include "../core/vec.hpp"
#include "emitters.hpp"
#include "lambertian.hpp"

namespace rt {

/// Why a path ended.
enum class path_end {
    escaped,     ///< it left the scene: the background
    max_bounces, ///< it made the most bounces path_options allows
    absorbed,    ///< the surface reflects nothing (kd 0), or the direction had no density
    roulette,    ///< Russian roulette ended it
};

/// The observer that hears nothing; each call is the moment of the path it names.
struct no_path_observer {
    /// The path meets a surface at `hit`, arriving with `throughput`.
    void surface(const hit_record& /*hit*/, const color& /*throughput*/) {}
    /// The surface glows with Le, counted with `weight` (mis.hpp).
    void emission(const color& /*Le*/, real /*weight*/) {}
    /// Next-event estimation: the light point `y`, the estimate before its weight,
    /// whether the shadow ray reached y, and the weight (0 where it did not).
    void light(const emitter_sample& /*y*/, const color& /*estimate*/, bool /*visible*/, real /*weight*/) {}
    /// What this surface adds to the pixel (its emission and its light, weighted).
    void added(const color& /*contribution*/) {}
    /// The next direction drawn from the surface.
    void bounce(const bsdf_sample& /*next*/) {}
    /// Russian roulette was played: whether the path goes on.
    void roulette(bool /*survived*/) {}
    /// The path ends: why, what the background added (for `escaped`), its radiance,
    /// and how many rays it traced after the camera ray (bounces' rays and shadow rays;
    /// told once, at the end, so that no count is kept in memory ray by ray).
    void end(path_end /*why*/, const color& /*background_added*/, const color& /*radiance*/,
             std::uint64_t /*rays*/)
    {
    }
};

/// Counts the rays a path traces after its camera ray into *count.
struct ray_count_observer : no_path_observer {
    std::uint64_t* count = nullptr;

    explicit ray_count_observer(std::uint64_t* counter) : count(counter) {}
    void end(path_end, const color&, const color&, std::uint64_t rays) { *count += rays; }
};

} // namespace rt
