// path_story.hpp - the story of one path, point by point (stage 11's --pixel):
// what path_story_recorder, an observer of rt::path_radiance (path_observer.hpp),
// writes down as the path goes.
//
//     rt::path_story story;
//     rt::path_radiance(s, accel, lights, camera_ray, rng, options, rt::path_story_recorder{&story});
//     for (const rt::path_vertex& v : story.vertices) ...
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "../core/config.hpp"
#include "../core/hit_record.hpp"
#include "../core/vec.hpp"
#include "emitters.hpp"
#include "lambertian.hpp"
#include "path_observer.hpp"

namespace rt {

/// One point of a path, for its story.
struct path_vertex {
    vec3 point{0};
    vec3 normal{0};
    int material = -1;
    color throughput{1.0f};   ///< arriving here
    color emitted{0.0f};      ///< Le of the surface (0: none)
    real emitted_weight = 0;  ///< its weight (mis.hpp)
    bool light_sampled = false;
    vec3 light_point{0};
    bool light_visible = false;
    color light_estimate{0.0f};  ///< next_event_estimate, before its weight
    real light_weight = 0;
    bool bounced = false;        ///< a next direction was drawn
    vec3 direction{0};
    real pdf = 0;
    color weight{0.0f};          ///< f cos / pdf
    bool roulette_played = false;
    bool survived = true;
    color added{0.0f};           ///< what this point added to the pixel
};

/// A path's story: its points, how it ended, and its radiance.
struct path_story {
    std::vector<path_vertex> vertices;
    bool escaped = false;        ///< it left the scene
    color background_added{0.0f};
    std::string ending;          ///< in words
    color radiance{0.0f};
};

/// The observer that writes the path into *story (which it clears first).
struct path_story_recorder : no_path_observer {
    path_story* story = nullptr;

    explicit path_story_recorder(path_story* into) : story(into) { *story = path_story{}; }

    void surface(const hit_record& hit, const color& throughput)
    {
        path_vertex v;
        v.point = hit.point;
        v.normal = hit.normal;
        v.material = hit.material;
        v.throughput = throughput;
        story->vertices.push_back(v);
    }
    void emission(const color& Le, real weight)
    {
        story->vertices.back().emitted = Le;
        story->vertices.back().emitted_weight = weight;
    }
    void light(const emitter_sample& y, const color& estimate, bool visible, real weight)
    {
        path_vertex& v = story->vertices.back();
        v.light_sampled = true;
        v.light_point = y.point;
        v.light_estimate = estimate;
        v.light_visible = visible;
        v.light_weight = weight;
    }
    void added(const color& contribution) { story->vertices.back().added = contribution; }
    void bounce(const bsdf_sample& next)
    {
        path_vertex& v = story->vertices.back();
        v.bounced = true;
        v.direction = next.direction;
        v.pdf = next.pdf;
        v.weight = next.weight;
    }
    void roulette(bool survived)
    {
        story->vertices.back().roulette_played = true;
        story->vertices.back().survived = survived;
    }
    void end(path_end why, const color& background_added, const color& radiance, std::uint64_t /*rays*/)
    {
        story->escaped = why == path_end::escaped;
        story->background_added = background_added;
        story->radiance = radiance;
        // at the most bounces, the last point is bounce max_bounces: one more than that many points before it
        story->ending = why == path_end::escaped ? "left the scene: the background"
                        : why == path_end::max_bounces
                            ? "ended: the most bounces a path may make (" +
                                  std::to_string(story->vertices.empty() ? 0 : story->vertices.size() - 1) + ")"
                        : why == path_end::roulette ? "ended by Russian roulette"
                                                    : "ended: the surface reflects nothing (kd 0)";
    }
};

} // namespace rt
