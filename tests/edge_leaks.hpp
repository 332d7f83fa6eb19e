// edge_leaks.hpp - rays from inside a closed mesh at its vertices and edges,
// and what a fused multiply-add in the watertight test's edge functions does
// to them (library_watertight.cpp, and docs_figures.cpp for the stage-04
// page's figures: both run icosphere_edge_leaks).
//
// The watertight test (Woop, Benthin, Wald 2013; include/rt/intersection/watertight.hpp)
// computes the edge function of an edge shared by two triangles from the same
// two sheared corners in both, as a b - c d in one and c d - a b in the other:
// exact negatives, so no ray passes between them. A compiler that contracts
// a b - c d into fma(a, b, -c d) rounds one product and not the other, and
// the two triangles then round differently. fused_watertight_hits is the test
// as such a compiler would make it (std::fma written out); the library rounds
// each product on its own (rt::detail::rounded_product).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include <rt/scene/mesh.hpp>
#include <rt/core/ray.hpp>
#include <rt/scene/triangle_shape.hpp>
#include <rt/core/vec.hpp>
#include <rt/intersection/watertight.hpp>

#include "test_scenes.hpp" // icosphere

namespace rt_test {

/// A target on a closed mesh's surface that rays from inside are aimed at,
/// with the triangles it lies on.
struct surface_target {
    rt::vec3 point;
    std::vector<std::size_t> triangles;
};

/// Every vertex (with its fan), every edge's midpoint and seven points along
/// it (with the edge's two triangles).
inline std::vector<surface_target> vertex_and_edge_targets(const rt::mesh& m)
{
    std::vector<surface_target> targets(m.positions.size());
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> edges;
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        const rt::index3& f = m.triangles[i];
        for (int k = 0; k < 3; ++k) {
            targets[f[std::size_t(k)]].triangles.push_back(i);
            const std::uint32_t a = f[std::size_t(k)], b = f[std::size_t((k + 1) % 3)];
            edges[{std::min(a, b), std::max(a, b)}].push_back(i);
        }
    }
    for (std::size_t v = 0; v < m.positions.size(); ++v)
        targets[v].point = m.positions[v];
    for (const auto& [edge, triangles] : edges) {
        const rt::vec3 a = m.positions[edge.first], b = m.positions[edge.second];
        targets.push_back({(a + b) * rt::real(0.5), triangles});
        for (int k = 1; k < 8; ++k)
            if (k != 4)
                targets.push_back({a + (rt::real(k) / 8) * (b - a), triangles});
    }
    return targets;
}

/// Whether the watertight test, with its edge functions contracted as
/// fma(a, b, -(c d)), hits the triangle v[0..8] at a t > 0: the translation
/// and shear of intersect_watertight, then the sign test on the fused values.
inline bool fused_watertight_hits(const rt::watertight_ray& w, const rt::real* v)
{
    const int kx = w.kx, ky = w.ky, kz = w.kz;
    rt::real X[3], Y[3], Z[3];
    for (int i = 0; i < 3; ++i) {
        const rt::real z = v[3 * i + kz] - w.p[kz];
        X[i] = (v[3 * i + kx] - w.p[kx]) - w.Sx * z;
        Y[i] = (v[3 * i + ky] - w.p[ky]) - w.Sy * z;
        Z[i] = w.Sz * z;
    }
    auto fused = [](rt::real a, rt::real b, rt::real c, rt::real d) { return std::fma(a, b, -(c * d)); };
    const rt::real U = fused(X[2], Y[1], Y[2], X[1]);
    const rt::real V = fused(X[0], Y[2], Y[0], X[2]);
    const rt::real W = fused(X[1], Y[0], Y[1], X[0]);
    if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0))
        return false;
    const rt::real det = U + V + W;
    return det != 0 && (U * Z[0] + V * Z[1] + W * Z[2]) / det > 0;
}

/// Rays from each origin (inside the closed, convex mesh m) to each vertex
/// and edge target, and how many of them leave without a hit on the target's
/// triangles: with the edge functions fused, and with the library's test.
struct edge_leak_count {
    std::size_t rays = 0, fused_leaks = 0, library_leaks = 0;
};

inline edge_leak_count count_edge_leaks(const rt::mesh& m, const std::vector<rt::vec3>& origins)
{
    edge_leak_count count;
    const std::vector<surface_target> targets = vertex_and_edge_targets(m);
    for (const rt::vec3& origin : origins)
        for (const surface_target& target : targets) {
            const rt::ray ray{origin, target.point - origin};
            const rt::watertight_ray w = rt::make_watertight_ray(ray);
            bool fused = false, library = false;
            for (std::size_t i : target.triangles) {
                const rt::index3& f = m.triangles[i];
                rt::real v[9];
                for (int c = 0; c < 3; ++c)
                    for (int k = 0; k < 3; ++k)
                        v[3 * c + k] = m.positions[f[std::size_t(c)]][k];
                rt::triangle_hit hit;
                fused = fused || fused_watertight_hits(w, v);
                library = library || rt::intersect_watertight(w, v, 0, rt::infinity, hit);
            }
            ++count.rays;
            count.fused_leaks += fused ? 0 : 1;
            count.library_leaks += library ? 0 : 1;
        }
    return count;
}

/// The case library_watertight runs and the stage-04 page quotes: an
/// icosphere of 1280 triangles seen from its centre and two other points
/// inside.
inline edge_leak_count icosphere_edge_leaks()
{
    const rt::vec3 c(rt::real(0.3), rt::real(-0.7), rt::real(0.2));
    const rt::real r = rt::real(1.7);
    return count_edge_leaks(icosphere(3, c, r),
                            {c, c + r * rt::vec3(0.3f, -0.2f, 0.1f), c + r * rt::vec3(-0.45f, 0.35f, 0.3f)});
}

} // namespace rt_test
