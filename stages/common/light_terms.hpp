// light_terms.hpp - the light terms of a pixel's story (pixel_story.hpp):
// what each light added at each recorded hit, worked out again from the hits
// and the shadow queries. Apart from pixel_story.hpp because it calls
// rt::sample_light, and so reaches stage 10's area_light.hpp: only the files
// that tell a story's light terms recompile when that header changes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>

#include <glm/geometric.hpp>

#include <rt/scene/light.hpp>
#include <rt/scene/light_sample.hpp>
#include <rt/core/ray.hpp>
#include <rt/scene/scene.hpp>
#include <rt/core/vec.hpp>

#include "pixel_story.hpp"

namespace stage {

/// Where the line of ray r first meets the area light `source` (a rect or a
/// sphere light), within a small tolerance; nullopt when it passes by. The
/// story finds the random point a shadow ray aimed at this way (stage 10).
inline std::optional<rt::vec3> point_on_light(const rt::light& source, const rt::ray& r)
{
    if (source.kind == rt::light_kind::rect) {
        const rt::vec3 n = glm::cross(source.edge1, source.edge2);
        const rt::real across = glm::dot(r.direction, n);
        if (across == 0)
            return std::nullopt;
        const rt::vec3 p = r.origin + (glm::dot(source.position - r.origin, n) / across) * r.direction;
        // p - corner = a edge1 + b edge2, both within [0, 1]
        const rt::vec3 q = p - source.position;
        const double aa = double(glm::dot(source.edge1, source.edge1)), ab = double(glm::dot(source.edge1, source.edge2));
        const double bb = double(glm::dot(source.edge2, source.edge2));
        const double qa = double(glm::dot(q, source.edge1)), qb = double(glm::dot(q, source.edge2));
        const double det = aa * bb - ab * ab, a = (qa * bb - qb * ab) / det, b = (qb * aa - qa * ab) / det;
        const double slack = 1e-3;
        if (a < -slack || a > 1 + slack || b < -slack || b > 1 + slack)
            return std::nullopt;
        return p;
    }
    if (source.kind == rt::light_kind::sphere) {
        const rt::vec3 d = glm::normalize(r.direction), oc = r.origin - source.position;
        const double half_b = double(glm::dot(oc, d));
        const double c = double(glm::dot(oc, oc)) - double(source.radius) * double(source.radius);
        if (c <= 0) // a point inside the light sees it from its centre (light_sample.hpp)
            return source.position;
        const double disc = half_b * half_b - c;
        if (disc < -1e-3 * double(source.radius) * double(source.radius))
            return std::nullopt;
        return r.origin + rt::real(-half_b - std::sqrt(std::max(0.0, disc))) * d;
    }
    return std::nullopt;
}

/// The light terms of every recorded hit, worked out as rt::direct_lighting
/// does (FCG eq. 4.3): a light behind the surface adds nothing; otherwise the
/// next shadow query in the log (when `shadows`) says whether it is visible;
/// a visible light adds blinn_phong(m, n, v, l, I). `shade` is the stage's
/// Blinn-Phong (rt::blinn_phong), passed in so this header needs no exercise.
/// `sampled`: the pixel was traced with random numbers (stage 10), so each
/// area light shone from a random point of it, the one its shadow ray aimed at
/// (an area light with no shadow ray of its own was behind the surface).
template <class Shade>
void explain_lights(story& s, const rt::scene& sc, bool shadows, bool falloff, Shade&& shade, bool sampled = false)
{
    std::size_t next_any = 0;
    for (std::size_t k = 0; k < s.queries.size(); ++k) {
        const query_record& q = s.queries[k];
        if (q.what != query_record::kind::closest || !q.hit)
            continue;
        const rt::material& m = sc.material_of(q.rec.material);
        s.ambient.push_back(m.ka * sc.ambient);
        const rt::vec3 v = -glm::normalize(q.r.direction);
        next_any = std::max(next_any, k + 1);
        for (std::size_t n = 0; n < sc.lights.size(); ++n) {
            light_term t;
            t.query = k;
            t.light = n;
            t.sample = rt::sample_light(sc.lights[n], q.rec.point, falloff);
            t.behind = glm::dot(q.rec.geometric_normal, t.sample.l) <= 0;
            const bool area = sampled && rt::is_area_light(sc.lights[n]);
            if (area) { // the random point is where the next shadow ray aimed, if it aimed at this light
                while (next_any < s.queries.size() && s.queries[next_any].what != query_record::kind::any)
                    ++next_any;
                const std::optional<rt::vec3> aimed =
                    next_any < s.queries.size() ? point_on_light(sc.lights[n], s.queries[next_any].r) : std::nullopt;
                t.behind = !aimed;
                if (aimed) { // for this sample, a point light there
                    rt::light at = sc.lights[n];
                    at.kind = rt::light_kind::point;
                    at.position = *aimed;
                    t.sample = rt::sample_light(at, q.rec.point, falloff);
                }
            }
            if (!t.behind && shadows) {
                while (next_any < s.queries.size() && s.queries[next_any].what != query_record::kind::any)
                    ++next_any;
                if (next_any < s.queries.size()) {
                    t.shadow_query = next_any;
                    t.visible = !s.queries[next_any].hit;
                    s.queries[next_any].role =
                        "shadow (light " + std::to_string(n) + (area ? ", a random point of it)" : ")");
                    ++next_any;
                }
            }
            if (!t.behind && t.visible)
                t.term = shade(m, q.rec.normal, v, t.sample.l, t.sample.intensity);
            s.lights.push_back(t);
        }
    }
}

} // namespace stage
