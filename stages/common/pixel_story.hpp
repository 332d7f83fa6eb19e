// pixel_story.hpp - "what happened to the ray through this pixel?": the story
// a stage program tells with --pixel I J (text) or --pixel-json I J (JSON).
//
//     stage07_reflections scenes/showcase.scene --pixel 320 200
//
// I is the column from the left and J the row from the top, as an image
// viewer shows them (the stored image's own convention); the story also gives
// the book's (i, j), with j counted from the bottom (FCG sec. 4.3.1).
//
// How it is told: the stage's own code runs for that one pixel, exactly as it
// does for the image, but its queries go through `recording`, an accelerator
// that passes every closest_hit and any_hit on to the real one and writes
// down what was asked and what came back. So the story is the student's code's
// story: a wrong offset, a missing normalisation or a shadow ray that hits
// its own surface shows up in it. The light terms are worked out afterwards
// from the recorded hits, with the student's blinn_phong.
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <rt/core/hit_record.hpp>
#include <rt/scene/light.hpp>
#include <rt/core/ray.hpp>
#include <rt/scene/scene.hpp>
#include <rt/core/vec.hpp>

namespace stage {

/// One question asked of the scene while the pixel's color was computed.
struct query_record {
    enum class kind { closest, any };
    kind what = kind::closest;
    rt::ray r;
    rt::real tmin = 0, tmax = 0;
    bool hit = false;
    rt::hit_record rec;                     ///< closest: the hit; any: the nearest blocker in [tmin, tmax]
    std::string role;                       ///< "camera", "reflection 1", "shadow (light 0)", ...
};

/// An accelerator that passes every query on to `inner` and records it.
/// Anything with closest_hit and any_hit (stage::world, a list) can be inner.
template <class Inner>
class recording {
public:
    recording(const Inner& inner, std::vector<query_record>& log) : inner_(&inner), log_(&log) {}

    bool closest_hit(const rt::ray& r, rt::real tmin, rt::real tmax, rt::hit_record& rec) const
    {
        const bool hit = inner_->closest_hit(r, tmin, tmax, rec);
        log_->push_back(query_record{query_record::kind::closest, r, tmin, tmax, hit, hit ? rec : rt::hit_record{}, ""});
        return hit;
    }

    bool any_hit(const rt::ray& r, rt::real tmin, rt::real tmax) const
    {
        const bool hit = inner_->any_hit(r, tmin, tmax);
        query_record q{query_record::kind::any, r, tmin, tmax, hit, rt::hit_record{}, ""};
        if (hit) // which shape blocked it: the nearest hit in the same interval
            inner_->closest_hit(r, tmin, tmax, q.rec);
        log_->push_back(q);
        return hit;
    }

private:
    const Inner* inner_;
    std::vector<query_record>* log_;
};

/// One light's part in the color of one hit (stages 05-07).
struct light_term {
    std::size_t query = 0;     ///< the closest-hit query whose hit this lights
    std::size_t light = 0;     ///< index into scene::lights
    rt::light_sample sample;   ///< l, distance, I at the hit point
    bool behind = false;       ///< the light is behind the surface: no term, no shadow ray
    bool visible = true;       ///< no shadow ray, or the shadow ray reached the light
    std::optional<std::size_t> shadow_query;  ///< the any-hit query that decided it
    rt::color term{0.0f};      ///< blinn_phong(m, n, v, l, I), or 0
};

/// Everything --pixel prints.
struct story {
    std::string program;
    int column = 0, row = 0;   ///< the image's convention: from the left, from the top
    int i = 0, j = 0;          ///< the book's: j from the bottom
    rt::ray camera;
    std::vector<query_record> queries;
    std::vector<light_term> lights;
    std::vector<rt::color> ambient;  ///< per closest-hit query with a hit: ka Ia (stages 05-07)
    rt::color linear{0.0f};          ///< the color the stage computed, before storing
    /// Further lines, in order: ("tone mapped", "0.5 0.25 0"), ("stored bytes", "186 137 0") ...
    std::vector<std::pair<std::string, std::string>> values;
};

/// The pixel's story as readable text / as one JSON object.
void print_story(std::ostream& out, const story& s, const rt::scene& sc);
void print_story_json(std::ostream& out, const story& s, const rt::scene& sc);

/// --pixel I J: checks the pixel lies in an nx x ny image (an rt::error
/// otherwise) and fills column, row, i and j.
void place_pixel(story& s, int column, int row, int nx, int ny);

/// Names each recorded query: the first closest-hit query is the camera ray;
/// a later one starts at an earlier hit (the nearest hit point to its origin),
/// and is "reflection k" when it leaves on the side the ray came from, or
/// "refraction k" (stage 09) when it goes through the surface, k being one
/// more than the bounces of that earlier ray; any-hit queries are shadow rays.
inline void name_queries(story& s)
{
    std::vector<int> depth(s.queries.size(), 0);
    bool camera_seen = false;
    for (std::size_t k = 0; k < s.queries.size(); ++k) {
        query_record& q = s.queries[k];
        if (q.what == query_record::kind::any) {
            q.role = "shadow";
            continue;
        }
        if (!camera_seen) {
            camera_seen = true;
            q.role = "camera";
            continue;
        }
        std::size_t parent = k;
        rt::real nearest = 0;
        for (std::size_t p = 0; p < k; ++p) {
            const query_record& earlier = s.queries[p];
            if (earlier.what != query_record::kind::closest || !earlier.hit)
                continue;
            const rt::real gap = glm::length(q.r.origin - earlier.rec.point);
            if (parent == k || gap < nearest) {
                parent = p;
                nearest = gap;
            }
        }
        if (parent == k) { // no earlier hit: a ray of its own
            q.role = "ray";
            continue;
        }
        depth[k] = depth[parent] + 1;
        const bool through = glm::dot(q.r.direction, s.queries[parent].rec.geometric_normal) < 0;
        q.role = (through ? "refraction " : "reflection ") + std::to_string(depth[k]);
    }
}

} // namespace stage
