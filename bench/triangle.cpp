// Experiment 3: triangle intersection, speed against leak rate on closed meshes.
//
// Closed, indexed meshes (every edge shared by exactly two triangles, the
// shared corners the same floats): an icosphere (the icosahedron subdivided
// twice, 320 triangles) and a double cone of 64 thin sides (128 triangles,
// 64 of them meeting at each apex). Both are moved off the origin and scaled,
// so that no coordinate is a round number. Rays start at random points inside
// and aim at
//   surface   uniform random points of random triangles;
//   edges     points of random edges, a + s (b - a) rounded to float;
//   vertices  the mesh's corners.
// A ray from inside a closed surface must hit it; one that hits no triangle
// has leaked. Each ray is tested against every triangle (the closest hit, as
// the course's list does), so the timing is that of the triangle test alone:
// we report million ray-triangle tests per second on one thread.
// Methods: Moller-Trumbore (rt::hit_triangle_moller_trumbore, the stage-04
// exercise), the watertight test as the library calls it for one triangle
// (rt::hit_triangle) and the watertight test with the per-ray set-up done once
// per ray, as the BVH does (rt::make_watertight_ray + rt::intersect_watertight).
//
// bench_triangle is compiled like every benchmark, without fused multiply-add
// contraction (-ffp-contract=off); bench_triangle_contract is the same source
// with -ffp-contract=fast and -march=native, as a user who asks for speed would
// compile it: where the CPU has FMA, a*b - c*d becomes fma(a, b, -c*d), the two
// triangles of an edge no longer compute exact negatives of each other, and
// the watertight test leaks. Its rows carry the method names with "+fma".
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <rt/core/random.hpp>
#include <rt/intersection/triangle.hpp>
#include <rt/intersection/watertight.hpp>

#include "bench.hpp"

namespace {

#if defined(RT_BENCH_CONTRACT)
constexpr bool contracted = true;
const std::string method_suffix = "+fma";
#else
constexpr bool contracted = false;
const std::string method_suffix;
#endif

using rt::real;
using rt::vec3;

struct closed_mesh {
    std::string name;
    std::vector<vec3> positions;
    std::vector<std::array<std::uint32_t, 3>> faces;
    vec3 inside{0};      ///< a point well inside
    real inside_radius;  ///< rays start within this distance of `inside`
};

/// The icosahedron subdivided `levels` times, the new vertices pushed onto the
/// unit sphere (each edge's midpoint made once, so the mesh stays indexed).
closed_mesh icosphere(int levels)
{
    const real g = real(1.618033988749895);
    std::vector<vec3> p = {{-1, g, 0}, {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
    for (vec3& v : p)
        v = glm::normalize(v);
    std::vector<std::array<std::uint32_t, 3>> f = {
        {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int l = 0; l < levels; ++l) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoint;
        auto middle = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto found = midpoint.find(key);
            if (found != midpoint.end())
                return found->second;
            p.push_back(glm::normalize(p[a] + p[b]));
            return midpoint[key] = std::uint32_t(p.size() - 1);
        };
        std::vector<std::array<std::uint32_t, 3>> next;
        for (const auto& t : f) {
            const std::uint32_t ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
            next.push_back({t[0], ab, ca});
            next.push_back({t[1], bc, ab});
            next.push_back({t[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        f = std::move(next);
    }
    closed_mesh m;
    m.name = "icosphere-" + std::to_string(f.size());
    m.positions = p;
    m.faces = f;
    m.inside_radius = real(0.5);
    return m;
}

/// Two cones of `sides` thin triangles each, base to base: every triangle meets
/// `sides` - 1 others at an apex.
closed_mesh double_cone(int sides)
{
    closed_mesh m;
    m.name = "double-cone-" + std::to_string(2 * sides);
    for (int k = 0; k < sides; ++k) {
        const double a = 2 * 3.141592653589793 * k / sides;
        m.positions.push_back(vec3(real(std::cos(a)), 0, real(std::sin(a))));
    }
    const auto top = std::uint32_t(sides), bottom = std::uint32_t(sides + 1);
    m.positions.push_back(vec3(0, real(1.7), 0));
    m.positions.push_back(vec3(0, real(-1.3), 0));
    for (int k = 0; k < sides; ++k) {
        const auto a = std::uint32_t(k), b = std::uint32_t((k + 1) % sides);
        m.faces.push_back({a, top, b});
        m.faces.push_back({b, bottom, a});
    }
    m.inside = vec3(0);
    m.inside_radius = real(0.3);
    return m;
}

/// Moves and scales the mesh so that no coordinate is a round number.
void place(closed_mesh& m)
{
    const vec3 shift(real(10.37), real(-3.11), real(5.93));
    const real scale = real(3.71);
    for (vec3& v : m.positions)
        v = v * scale + shift;
    m.inside = m.inside * scale + shift;
    m.inside_radius *= scale;
}

std::vector<rt::ray> make_rays(const closed_mesh& m, const std::string& kind, std::size_t count, std::uint64_t seed)
{
    rt::pcg32 rng(seed, 5);
    auto uniform = [&] { return real(rng.next_float()); };
    std::vector<rt::ray> rays;
    rays.reserve(count);
    while (rays.size() < count) {
        vec3 offset;
        do
            offset = vec3{2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1};
        while (glm::dot(offset, offset) > 1);
        const vec3 origin = m.inside + m.inside_radius * offset;
        const auto& face = m.faces[rng.next_below(std::uint32_t(m.faces.size()))];
        vec3 target;
        if (kind == "surface") {
            real u = uniform(), v = uniform();
            if (u + v > 1) {
                u = 1 - u;
                v = 1 - v;
            }
            target = m.positions[face[0]] + u * (m.positions[face[1]] - m.positions[face[0]]) +
                     v * (m.positions[face[2]] - m.positions[face[0]]);
        } else if (kind == "edges") {
            const std::uint32_t e = rng.next_below(3);
            const vec3& a = m.positions[face[e]];
            const vec3& b = m.positions[face[(e + 1) % 3]];
            target = a + uniform() * (b - a);
        } else {
            target = m.positions[face[rng.next_below(3)]];
        }
        const vec3 d = target - origin;
        if (glm::dot(d, d) > 0)
            rays.push_back(rt::ray{origin, d});
    }
    return rays;
}

} // namespace

int main(int argc, char** argv)
{
    return bench::run("bench_triangle", [&] {
        const bench::options o = bench::parse_options(argc, argv, "bench_triangle: experiment 3, triangle tests and leaks");
        const std::size_t count = o.quick ? 2000 : 100000;
        const int repeats = o.quick ? 1 : 3;
        std::vector<closed_mesh> meshes = {icosphere(2), double_cone(64)};
        bench::csv table("triangle intersection: speed against leak rate on closed meshes (bench/triangle.cpp)",
                         {"mesh", "triangles", "rays", "method", "ray_count", "seconds", "mtests_per_s",
                          "ns_per_test", "leaks", "leak_fraction"});
        table.note("contraction", contracted ? "-ffp-contract=fast (fused multiply-add allowed)"
                                             : "-ffp-contract=off (no fused multiply-add)");
        table.note("leak", "a ray from inside the closed mesh that hits none of its triangles (every triangle tested)");

        for (closed_mesh& m : meshes) {
            place(m);
            std::vector<rt::triangle> tris;
            std::vector<std::array<real, 9>> packed;
            for (const auto& f : m.faces) {
                const vec3 &a = m.positions[f[0]], &b = m.positions[f[1]], &c = m.positions[f[2]];
                tris.push_back(rt::triangle{a, b, c, -1});
                packed.push_back({a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z});
            }
            for (const std::string kind : {"surface", "edges", "vertices"}) {
                const std::vector<rt::ray> rays = make_rays(m, kind, count, 17);
                for (const std::string method : {"moller_trumbore", "watertight", "watertight_per_ray"}) {
                    std::size_t leaks = 0;
                    const double seconds = bench::best_time(repeats, [&] {
                        leaks = 0;
                        for (const rt::ray& r : rays) {
                            bool hit = false;
                            real closest = std::numeric_limits<real>::infinity();
                            if (method == "watertight_per_ray") {
                                const rt::watertight_ray w = rt::make_watertight_ray(r);
                                for (const auto& v : packed) {
                                    rt::triangle_hit h;
                                    if (rt::intersect_watertight(w, v.data(), real(0), closest, h)) {
                                        hit = true;
                                        closest = h.t;
                                    }
                                }
                            } else {
                                const bool mt = method == "moller_trumbore";
                                for (const rt::triangle& t : tris) {
                                    rt::hit_record rec;
                                    if (mt ? rt::hit_triangle_moller_trumbore(t, r, real(0), closest, rec)
                                           : rt::hit_triangle(t, r, real(0), closest, rec)) {
                                        hit = true;
                                        closest = rec.t;
                                    }
                                }
                            }
                            leaks += !hit;
                        }
                    });
                    const double tests = double(rays.size()) * double(tris.size());
                    table.row() << m.name << tris.size() << kind << (method + method_suffix) << rays.size() << seconds
                                << tests / seconds / 1e6 << seconds / tests * 1e9 << leaks
                                << double(leaks) / double(rays.size());
                    std::cout << m.name << ", " << kind << ", " << method << method_suffix << ": " << tests / seconds / 1e6
                              << " M tests/s, " << leaks << " leaks of " << rays.size() << '\n';
                }
            }
        }
        table.write(o, contracted ? "triangle_contract.csv" : "triangle.csv");
        return 0;
    });
}
