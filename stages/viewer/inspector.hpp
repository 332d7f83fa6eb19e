// inspector.hpp - the viewer's ray inspector: a pixel's story (the --pixel
// trace of stages/common/pixel_story.hpp) drawn over the image (no SDL here:
// main.cpp draws the segments this header computes).
//
//     const stage::story st = stage::shaded_story(scene, "stage08_output", column, row, nx, ny);
//     for (const viewer::overlay_segment& s : viewer::story_segments(st, gen, reach)) ...draw s.a -> s.b in s.what's color
//
// Each recorded query becomes a segment in the world, from its origin to what
// it hit (a closest hit), to its blocker or its end (a shadow ray), or to
// `reach` along it (a miss); the segment is then projected with the view's
// camera, so the rays stay where they are in the scene while the camera moves.
// The projection inverts generate_ray (camera.hpp, FCG 4th ed., sec. 4.3):
// a point p seen from the eye e in the frame (u, v, w) at distance
// depth = -(p - e).w lies on the image plane at u_s = d (p - e).u / depth,
// v_s = d (p - e).v / depth (perspective) or u_s = (p - e).u, v_s = (p - e).v
// (orthographic), which is the film position x = nx (u_s - l) / (r - l),
// y = ny (v_s - b) / (t - b) from the bottom; the window's row is ny - y.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include <rt/camera/camera.hpp>
#include <rt/core/ray.hpp>
#include <rt/core/vec.hpp>

#include "pixel_story.hpp"

namespace viewer {

/// A point of the window: x from the left, y from the top, in pixels (the
/// centre of pixel (column, row) is (column + 0.5, row + 0.5)).
struct window_point {
    double x = 0, y = 0;
};

/// The kinds of ray, each drawn in its own color.
enum class ray_kind { camera, shadow_visible, shadow_blocked, reflection, refraction, other };

inline const char* name_of(ray_kind k)
{
    switch (k) {
    case ray_kind::camera: return "camera";
    case ray_kind::shadow_visible: return "shadow (light visible)";
    case ray_kind::shadow_blocked: return "shadow (blocked)";
    case ray_kind::reflection: return "reflection";
    case ray_kind::refraction: return "refraction";
    case ray_kind::other: break;
    }
    return "ray";
}

/// The kind of a recorded query, from the role name_queries gave it.
inline ray_kind kind_of(const stage::query_record& q)
{
    if (q.what == stage::query_record::kind::any)
        return q.hit ? ray_kind::shadow_blocked : ray_kind::shadow_visible;
    if (q.role == "camera")
        return ray_kind::camera;
    if (q.role.rfind("reflection", 0) == 0)
        return ray_kind::reflection;
    if (q.role.rfind("refraction", 0) == 0)
        return ray_kind::refraction;
    return ray_kind::other;
}

/// How far in front of the eye a point must be to be projected (a fraction of d).
constexpr double near_fraction = 1e-4;

/// The image-plane coordinates (u_s, v_s) and the depth along -w of world point p.
struct plane_point {
    double u = 0, v = 0, depth = 0;
};

inline plane_point to_plane(const rt::ray_generator& gen, const rt::vec3& p)
{
    const rt::vec3 q = p - gen.e;
    const double qu = double(glm::dot(q, gen.basis.u)), qv = double(glm::dot(q, gen.basis.v));
    const double depth = -double(glm::dot(q, gen.basis.w));
    if (gen.kind == rt::projection::orthographic)
        return {qu, qv, depth};
    return {double(gen.d) * qu / depth, double(gen.d) * qv / depth, depth};
}

/// Where world point p shows in the window, or nothing when it lies behind the
/// eye (perspective; an orthographic camera shows every point).
inline std::optional<window_point> project(const rt::ray_generator& gen, const rt::vec3& p)
{
    const plane_point s = to_plane(gen, p);
    if (gen.kind == rt::projection::perspective && !(s.depth > near_fraction * double(gen.d)))
        return std::nullopt;
    const rt::window& win = gen.plane;
    const double x = double(gen.nx) * (s.u - double(win.l)) / double(win.r - win.l);
    const double y = double(gen.ny) * (s.v - double(win.b)) / double(win.t - win.b);
    return window_point{x, double(gen.ny) - y};
}

/// One segment to draw, in window coordinates.
struct overlay_segment {
    window_point a, b;
    ray_kind what = ray_kind::other;
    bool ends_at_hit = false; ///< b is a hit point (drawn as a dot)
};

/// The part of the world segment a -> b in front of the eye, projected; nothing
/// when all of it is behind (a perspective camera's segment is clipped at the
/// near distance, so a ray leaving the eye shows from just in front of it).
inline std::optional<std::pair<window_point, window_point>> project_segment(const rt::ray_generator& gen,
                                                                             rt::vec3 a, rt::vec3 b)
{
    if (gen.kind == rt::projection::perspective) {
        const double near = near_fraction * double(gen.d) * 2;
        const double da = to_plane(gen, a).depth, db = to_plane(gen, b).depth;
        if (da < near && db < near)
            return std::nullopt;
        if (da < near)
            a = a + (b - a) * rt::real((near - da) / (db - da));
        else if (db < near)
            b = b + (a - b) * rt::real((near - db) / (da - db));
    }
    const std::optional<window_point> pa = project(gen, a), pb = project(gen, b);
    if (!pa || !pb)
        return std::nullopt;
    return std::make_pair(*pa, *pb);
}

/// The part of segment a -> b inside the rectangle [x0, x1] x [y0, y1]
/// (Liang and Barsky's clipping), or nothing when it misses it: a projected
/// point far outside the window would overflow the drawing's integers.
inline std::optional<std::pair<window_point, window_point>> clip(window_point a, window_point b, double x0, double y0,
                                                                 double x1, double y1)
{
    double t0 = 0, t1 = 1;
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {a.x - x0, x1 - a.x, a.y - y0, y1 - a.y};
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0) {
            if (q[k] < 0)
                return std::nullopt; // parallel to this edge and outside it
            continue;
        }
        const double t = q[k] / p[k];
        if (p[k] < 0)
            t0 = std::max(t0, t);
        else
            t1 = std::min(t1, t);
    }
    if (t0 > t1)
        return std::nullopt;
    return std::make_pair(window_point{a.x + t0 * dx, a.y + t0 * dy}, window_point{a.x + t1 * dx, a.y + t1 * dy});
}

/// The segments of a pixel's story seen through `gen`; `reach` is how far a
/// ray that hit nothing is drawn (the scene's size, say).
inline std::vector<overlay_segment> story_segments(const stage::story& st, const rt::ray_generator& gen, double reach)
{
    std::vector<overlay_segment> out;
    for (const stage::query_record& q : st.queries) {
        const rt::vec3 a = q.r.origin;
        rt::vec3 b;
        bool at_hit = false;
        if (q.hit) {
            b = q.rec.point;
            at_hit = true;
        } else if (q.what == stage::query_record::kind::any && std::isfinite(double(q.tmax))) {
            b = q.r.at(q.tmax); // a segment to a point light, unblocked
        } else {
            const double length = double(glm::length(q.r.direction));
            b = q.r.origin + q.r.direction * rt::real(length > 0 ? reach / length : 0);
        }
        const auto seen = project_segment(gen, a, b);
        if (!seen)
            continue;
        out.push_back(overlay_segment{seen->first, seen->second, kind_of(q), at_hit});
    }
    return out;
}

} // namespace viewer
