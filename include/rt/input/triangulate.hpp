// triangulate.hpp - polygons of any number of corners into triangles, robustly.
//
// Usage:
//     std::vector<rt::vec3> corners = ...;                // one face, in order
//     rt::polygon_triangulation t = rt::triangulate_polygon(corners);
//     for (const rt::corner3& tri : t.triangles)          // corner numbers 0..n-1
//         use(corners[tri[0]], corners[tri[1]], corners[tri[2]]);
//     if (t.problem != rt::polygon_problem::none) ...     // t.triangles is the fallback
//
// What is promised. A simple polygon (its edges meet only at shared corners),
// convex or concave, planar in any orientation, gives n - 2 triangles, each
// inside it, whose areas add up to its area; the triangles keep the polygon's
// winding (their normals point along its Newell normal). "Weakly simple"
// polygons, whose boundary touches itself at repeated corners without
// crossing, count as simple: a ring written as one polygon, the outer circle
// joined to the inner one by a slit walked twice, as exporters write holes.
// A corner on the straight line between its neighbours is fine.
//
// How:
//  1. The polygon's plane: its Newell normal N, the sum over the edges (i, j)
//     of (y_i - y_j)(z_i + z_j), (z_i - z_j)(x_i + x_j), (x_i - x_j)(y_i + y_j)
//     (Newell's method: Sutherland, Sproull and Schumacker, "A
//     Characterization of Ten Hidden-Surface Algorithms", Computing Surveys
//     6(1), 1974; F. Tampieri, "Newell's Method for Computing the Plane
//     Equation of a Polygon", Graphics Gems III, 1992); |N| / 2 is its area.
//     The corners are projected onto the coordinate plane of N's largest
//     component by dropping that coordinate - exactly, no rounding - and
//     ordered so that the projection winds counter-clockwise.
//  2. Every decision is an orientation test, orient2d(a, b, c) = the sign of
//     (a - c) x (b - c), decided exactly (orient2d.hpp, after Shewchuk 1997).
//  3. A convex quad is split along the diagonal whose two triangles have the
//     larger smallest angle (of the two triangulations, the one that is
//     Delaunay: de Berg, Cheong, van Kreveld, Overmars, "Computational
//     Geometry", 3rd ed., 2008, ch. 9: the Delaunay triangulation maximises the
//     smallest angle). Any other polygon is cut by ear clipping (Meisters,
//     "Polygons have ears", Amer. Math. Monthly 82, 1975: every simple polygon
//     of 4 or more corners has two non-overlapping ears): a corner v with
//     neighbours p and n is an ear when v is strictly convex and no other
//     corner lies in the closed triangle p v n; a corner at the same place as
//     p, v or n (a repeated corner) blocks it only when one of its edges
//     leaves into the triangle. Ear states are kept and only the two
//     neighbours of a clipped ear are tested again: O(n^2) for n corners.
//
// What is reported (polygon_problem, with the fallback in `triangles`): fewer
// than 3 corners (no triangles); two consecutive corners at the same place (a
// zero-length edge: each run of them is merged into one corner and the rest
// triangulated, n - 2 - merged triangles); no area (N = 0 with all corners on a line); edges that cross or a
// corner lying inside another edge, or lobes whose areas cancel (not simple).
// The fallback is the fan from corner 0 (n - 2 triangles, which the OBJ loader
// keeps when their area is not zero, and reports: see obj_loader.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "orient2d.hpp"
#include "../core/vec.hpp"

namespace rt {

/// Three corner numbers of a polygon (0 .. n-1).
using corner3 = std::array<std::uint32_t, 3>;

enum class polygon_problem {
    none,
    too_few_corners,   ///< fewer than 3
    repeated_corner,   ///< two consecutive corners at the same place
    no_area,           ///< the Newell normal is zero
    not_simple,        ///< two edges cross, or a corner lies inside another edge
};

/// What went wrong, in words for a message ("two of its edges cross").
inline const char* to_string(polygon_problem problem)
{
    switch (problem) {
    case polygon_problem::none: return "a simple polygon";
    case polygon_problem::too_few_corners: return "fewer than 3 corners";
    case polygon_problem::repeated_corner: return "two consecutive corners at the same place";
    case polygon_problem::no_area: return "no area (its corners on one line)";
    case polygon_problem::not_simple: return "edges that cross or touch (not a simple polygon)";
    }
    return "";
}

struct polygon_triangulation {
    std::vector<corner3> triangles;
    polygon_problem problem = polygon_problem::none;
    /// for a problem: the corners (numbers) where it shows (two edges' first
    /// corners for crossing edges, the repeated corner twice, ...)
    std::uint32_t at[2] = {0, 0};
};

namespace detail {

using dvec3 = glm::dvec3;

/// The Newell normal (twice the vector area), summed in double.
inline dvec3 newell_normal(const std::vector<vec3>& corners)
{
    dvec3 n(0.0);
    const std::size_t count = corners.size();
    for (std::size_t i = 0; i < count; ++i) {
        const dvec3 p(corners[i]);
        const dvec3 q(corners[(i + 1) % count]);
        n.x += (p.y - q.y) * (p.z + q.z);
        n.y += (p.z - q.z) * (p.x + q.x);
        n.z += (p.x - q.x) * (p.y + q.y);
    }
    return n;
}

/// The cosine of the smallest angle of triangle a b c (the largest cosine of
/// its three): larger is worse. Used only to choose a quad's diagonal.
inline double largest_cosine(const dvec3& a, const dvec3& b, const dvec3& c)
{
    const auto cosine = [](const dvec3& at, const dvec3& u, const dvec3& v) {
        const dvec3 e1 = u - at, e2 = v - at;
        const double lengths = std::sqrt(glm::dot(e1, e1) * glm::dot(e2, e2));
        return lengths > 0 ? glm::dot(e1, e2) / lengths : 1.0;
    };
    return std::max({cosine(a, b, c), cosine(b, c, a), cosine(c, a, b)});
}

/// The fallback: the fan from corner 0.
inline std::vector<corner3> fan(std::size_t count)
{
    std::vector<corner3> triangles;
    for (std::size_t i = 1; i + 1 < count; ++i)
        triangles.push_back({0, std::uint32_t(i), std::uint32_t(i + 1)});
    return triangles;
}

/// Ear clipping of a counter-clockwise weakly simple polygon (see the top).
inline std::vector<corner3> clip_ears(const std::vector<dvec2>& p)
{
    const std::size_t count = p.size();
    std::vector<std::uint32_t> prev(count), next(count);
    for (std::size_t i = 0; i < count; ++i) {
        prev[i] = std::uint32_t((i + count - 1) % count);
        next[i] = std::uint32_t((i + 1) % count);
    }
    // a corner q at the same place as triangle corner `c` (whose edges in the
    // triangle go to u and w, counter-clockwise u then w) blocks when an edge
    // of q leaves into the open wedge at c
    const auto enters_wedge = [&](const dvec2& c, const dvec2& u, const dvec2& w, const dvec2& x) {
        return orient2d(c, u, x) > 0 && orient2d(c, x, w) > 0;
    };
    const auto is_ear = [&](std::uint32_t v) {
        const std::uint32_t a = prev[v], b = next[v];
        if (orient2d(p[a], p[v], p[b]) <= 0)
            return false;
        for (std::uint32_t q = next[b]; q != a; q = next[q]) {
            const dvec2& x = p[q];
            if (x == p[a] || x == p[v] || x == p[b]) {
                const dvec2& c = x;
                const dvec2 u = x == p[a] ? p[v] : x == p[v] ? p[b] : p[a];
                const dvec2 w = x == p[a] ? p[b] : x == p[v] ? p[a] : p[v];
                if (enters_wedge(c, u, w, p[prev[q]]) || enters_wedge(c, u, w, p[next[q]]))
                    return false;
                continue;
            }
            if (orient2d(p[a], p[v], x) >= 0 && orient2d(p[v], p[b], x) >= 0 && orient2d(p[b], p[a], x) >= 0)
                return false; // inside the closed triangle
        }
        return true;
    };
    std::vector<char> ear(count, 0);
    for (std::uint32_t v = 0; v < count; ++v)
        ear[v] = is_ear(v);
    std::vector<corner3> triangles;
    triangles.reserve(count - 2);
    std::size_t left = count;
    std::uint32_t v = 0;
    while (left > 3) {
        std::uint32_t found = v;
        std::size_t looked = 0;
        while (!ear[found] && looked < left) {
            found = next[found];
            ++looked;
        }
        if (!ear[found]) {
            // no ear: only a polygon that is not (weakly) simple gets here,
            // which the caller tested first; end with a fan of what is left
            for (std::uint32_t q = next[found]; next[q] != found; q = next[q])
                triangles.push_back({found, q, next[q]});
            return triangles;
        }
        const std::uint32_t a = prev[found], b = next[found];
        triangles.push_back({a, found, b});
        next[a] = b;
        prev[b] = a;
        --left;
        ear[a] = is_ear(a);
        ear[b] = is_ear(b);
        v = b;
    }
    triangles.push_back({prev[v], v, next[v]});
    return triangles;
}

} // namespace detail

/// Triangulates one polygon (see the top of this file). The result's corner
/// numbers index `corners`.
inline polygon_triangulation triangulate_polygon(const std::vector<vec3>& corners)
{
    polygon_triangulation result;
    const std::size_t count = corners.size();
    if (count < 3) {
        result.problem = polygon_problem::too_few_corners;
        return result;
    }
    if (count == 3) {
        result.triangles.push_back({0, 1, 2});
        return result;
    }
    for (std::size_t i = 0; i < count; ++i)
        if (corners[i] == corners[(i + 1) % count]) {
            // merge each run of repeated corners into one and triangulate the
            // rest: n - 2 - (merged) triangles
            std::vector<std::uint32_t> kept;
            std::vector<vec3> rest;
            for (std::size_t k = 0; k < count; ++k)
                if (corners[k] != corners[(k + 1) % count]) {
                    kept.push_back(std::uint32_t(k));
                    rest.push_back(corners[k]);
                }
            polygon_triangulation merged = triangulate_polygon(rest);
            for (corner3& tri : merged.triangles)
                for (std::uint32_t& corner : tri)
                    corner = kept[corner];
            result.triangles = std::move(merged.triangles);
            result.problem = merged.problem == polygon_problem::none ? polygon_problem::repeated_corner : merged.problem;
            result.at[0] = std::uint32_t(i);
            result.at[1] = std::uint32_t((i + 1) % count);
            return result;
        }
    const detail::dvec3 n = detail::newell_normal(corners);
    const detail::dvec3 size(std::fabs(n.x), std::fabs(n.y), std::fabs(n.z));
    const int drop = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
    if (!(size[drop] > 0)) {
        // no net area: all corners on a line, or lobes winding opposite ways
        // that cancel (a symmetric bow tie), which is not simple
        result.problem = polygon_problem::no_area;
        const detail::dvec3 first(corners[0]);
        for (std::size_t i = 1; i + 1 < count; ++i) {
            const detail::dvec3 twice_area =
                glm::cross(detail::dvec3(corners[i]) - first, detail::dvec3(corners[i + 1]) - first);
            if (twice_area != detail::dvec3(0.0)) {
                result.problem = polygon_problem::not_simple;
                result.at[0] = 0;
                result.at[1] = std::uint32_t(i);
                break;
            }
        }
        result.triangles = detail::fan(count);
        return result;
    }
    // the two remaining axes, in the order that makes the projection of a
    // polygon winding counter-clockwise about +axis stay counter-clockwise:
    // (y, z) for x, (z, x) for y, (x, y) for z; reversed when N points along -axis
    const int u_axis = (drop + 1) % 3, v_axis = (drop + 2) % 3;
    const bool flip = n[drop] < 0;
    std::vector<detail::dvec2> projected(count);
    for (std::size_t i = 0; i < count; ++i) {
        const double u = double(corners[i][u_axis]), v = double(corners[i][v_axis]);
        projected[i] = flip ? detail::dvec2(v, u) : detail::dvec2(u, v);
    }
    // simple? no two edges cross, no corner inside another edge: O(n^2)
    for (std::size_t i = 0; i < count; ++i) {
        const detail::dvec2& a = projected[i];
        const detail::dvec2& b = projected[(i + 1) % count];
        for (std::size_t j = i + 1; j < count; ++j) {
            const detail::dvec2& c = projected[j];
            const detail::dvec2& d = projected[(j + 1) % count];
            const bool adjacent = j == i + 1 || (i == 0 && j == count - 1);
            if ((!adjacent && detail::proper_crossing(a, b, c, d)) || detail::inside_segment(c, a, b) ||
                detail::inside_segment(a, c, d)) {
                result.problem = polygon_problem::not_simple;
                result.at[0] = std::uint32_t(i);
                result.at[1] = std::uint32_t(j);
                result.triangles = detail::fan(count);
                return result;
            }
        }
    }
    if (count == 4) {
        bool convex = true;
        for (std::size_t i = 0; i < 4; ++i)
            convex = convex && detail::orient2d(projected[i], projected[(i + 1) % 4], projected[(i + 2) % 4]) > 0;
        if (convex) {
            const detail::dvec3 a(corners[0]), b(corners[1]), c(corners[2]), d(corners[3]);
            // diagonal 0-2: triangles 0 1 2 and 0 2 3; diagonal 1-3: 0 1 3 and 1 2 3
            const double along_02 = std::max(detail::largest_cosine(a, b, c), detail::largest_cosine(a, c, d));
            const double along_13 = std::max(detail::largest_cosine(a, b, d), detail::largest_cosine(b, c, d));
            if (along_02 <= along_13)
                result.triangles = {{0, 1, 2}, {0, 2, 3}};
            else
                result.triangles = {{0, 1, 3}, {1, 2, 3}};
            return result;
        }
    }
    result.triangles = detail::clip_ears(projected);
    return result;
}

} // namespace rt
