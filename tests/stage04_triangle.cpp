// Stage 04 - triangles, meshes and groups.
//
// Expected values are worked out by hand (Moller, Trumbore 1997; Woop, Benthin,
// Wald 2013; see include/rt/triangle.hpp), or are properties: a closed mesh
// seen from inside is hit by every ray (watertightness); a ray spawned from a
// hit does not hit the same surface again (PBR 3rd ed., sec. 3.9.5); the BVH
// returns exactly what the list of all shapes returns. Where a method fails
// (Moller-Trumbore leaks, a naive or fixed-epsilon ray start re-hits, a slab
// test without Ize's factor culls), the test counts the failures and asserts
// that there are some; docs/stages/04-triangle.md shows the numbers.
//
// Only stage-04 exercises (Moller-Trumbore, closest_hit_list) and unmarked
// library code are called: scenes, meshes and rays are built here.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <rt/bvh.hpp>
#include <rt/intersect.hpp>
#include <rt/obj_loader.hpp>
#include <rt/offset.hpp>
#include <rt/spawn.hpp>
#include <rt/triangle.hpp>

namespace {

using rt::real;
using rt::vec3;

constexpr bool in_float = std::is_same_v<real, float>;
const real tol = in_float ? real(1e-5) : real(1e-12);

bool near(real got, real want, real eps = tol)
{
    return std::fabs(got - want) <= eps * std::max(real(1), std::fabs(want));
}

bool near(const vec3& got, const vec3& want, real eps = tol)
{
    return near(got.x, want.x, eps) && near(got.y, want.y, eps) && near(got.z, want.z, eps);
}

// --- meshes built here ------------------------------------------------------

/// A unit icosahedron subdivided `levels` times (each triangle into four, the
/// new corners pushed onto the sphere), then scaled and moved. Corners shared
/// by neighbouring triangles are one index, so the mesh is closed; every face
/// is counter-clockwise seen from outside.
rt::mesh icosphere(int levels, const vec3& center, real radius)
{
    const double g = (1 + std::sqrt(5.0)) / 2;
    std::vector<std::array<double, 3>> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                            {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    std::vector<rt::index3> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                     {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                     {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                     {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    auto unit = [](std::array<double, 3> v) {
        const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        return std::array<double, 3>{v[0] / l, v[1] / l, v[2] / l};
    };
    for (auto& v : p)
        v = unit(v);
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::make_pair(std::min(a, b), std::max(a, b));
            const auto found = middle.find(key);
            if (found != middle.end())
                return found->second;
            p.push_back(unit({p[a][0] + p[b][0], p[a][1] + p[b][1], p[a][2] + p[b][2]}));
            const auto index = std::uint32_t(p.size() - 1);
            middle[key] = index;
            return index;
        };
        std::vector<rt::index3> finer;
        for (const rt::index3& f : faces) {
            const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            finer.push_back({f[0], ab, ca});
            finer.push_back({f[1], bc, ab});
            finer.push_back({f[2], ca, bc});
            finer.push_back({ab, bc, ca});
        }
        faces = finer;
    }
    rt::mesh m;
    for (const auto& v : p)
        m.positions.push_back(center + radius * vec3(real(v[0]), real(v[1]), real(v[2])));
    for (rt::index3 f : faces) { // make every face counter-clockwise seen from outside
        const vec3 a = m.positions[f[0]] - center, b = m.positions[f[1]] - center, c = m.positions[f[2]] - center;
        if (glm::dot(glm::cross(b - a, c - a), a + b + c) < 0)
            std::swap(f[1], f[2]);
        m.triangles.push_back(f);
    }
    return m;
}

rt::mesh cube_from_file()
{
    return rt::load_obj(RT_TEST_DATA_DIR "/cube.obj").geometry;
}

rt::scene scene_of(rt::mesh m)
{
    rt::scene s;
    s.shapes.emplace_back(std::move(m));
    return s;
}

rt::aabb bounds_of(const rt::mesh& m)
{
    rt::aabb box;
    for (const vec3& p : m.positions)
        box.grow(p);
    return box;
}

/// Targets on a closed mesh's surface that rays from inside are aimed at,
/// each with the triangles it lies on: every vertex (its fan), every edge's
/// midpoint and seven points along it (the edge's two triangles).
struct surface_target {
    vec3 point;
    std::vector<std::size_t> triangles;
};

std::vector<surface_target> vertex_and_edge_targets(const rt::mesh& m)
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
        const vec3 a = m.positions[edge.first], b = m.positions[edge.second];
        targets.push_back({(a + b) * real(0.5), triangles});
        for (int k = 1; k < 8; ++k)
            if (k != 4)
                targets.push_back({a + (real(k) / 8) * (b - a), triangles});
    }
    return targets;
}

// --- files written by the OBJ tests ---------------------------------------------

std::filesystem::path scratch_folder(const std::string& name)
{
    const std::filesystem::path folder = std::filesystem::temp_directory_path() / ("rt-stage04-" + name);
    std::filesystem::create_directories(folder);
    return folder;
}

std::filesystem::path write_file(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

std::string load_error(const std::filesystem::path& path, const rt::obj_limits& limits = {})
{
    try {
        rt::load_obj(path, limits);
    } catch (const rt::error& e) {
        return e.what();
    }
    return "no error";
}

bool one_line(const std::string& text)
{
    return text.find('\n') == std::string::npos && text.find('\r') == std::string::npos;
}

} // namespace

// =============================================================================
// One triangle, worked out by hand
// =============================================================================

TEST_CASE("Moller-Trumbore and the watertight test find t and the barycentrics worked out by hand")
{
    // a = (0,0,0), b = (1,0,0), c = (0,1,0): counter-clockwise seen from +z, so
    // the front normal is +z. A ray down the z axis through (x, y) hits at
    // b1 = x, b2 = y, b0 = 1 - x - y, t = (height of the origin) / |d_z|.
    const rt::triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 4};
    struct method {
        const char* name;
        bool (*hit)(const rt::triangle&, const rt::ray&, real, real, rt::hit_record&);
    };
    const method methods[] = {{"Moller-Trumbore", rt::hit_triangle_moller_trumbore}, {"watertight", rt::hit_triangle}};
    for (const method& m : methods) {
        const std::string method_name = m.name;
        CAPTURE(method_name);
        rt::hit_record rec;
        REQUIRE(m.hit(tri, rt::ray{{0.25f, 0.5f, 2}, {0, 0, -1}}, 0, 10, rec));
        CHECK(near(rec.t, 2));
        CHECK(near(rec.b1, real(0.25)));
        CHECK(near(rec.b2, real(0.5)));
        CHECK(near(rec.point, vec3(0.25f, 0.5f, 0)));
        CHECK(rec.front_face);
        CHECK(near(rec.geometric_normal, vec3(0, 0, 1)));
        CHECK(near(rec.normal, vec3(0, 0, 1)));
        CHECK(rec.material == 4);

        // from below: two-sided, the back face, normals turned towards the ray;
        // a direction of length 2 halves t
        REQUIRE(m.hit(tri, rt::ray{{0.25f, 0.5f, -3}, {0, 0, 2}}, 0, 10, rec));
        CHECK(near(rec.t, real(1.5)));
        CHECK_FALSE(rec.front_face);
        CHECK(near(rec.geometric_normal, vec3(0, 0, -1)));

        // misses: beyond each edge, parallel in the plane, behind the origin
        CHECK_FALSE(m.hit(tri, rt::ray{{0.6f, 0.6f, 1}, {0, 0, -1}}, 0, 10, rec));  // u + v > 1
        CHECK_FALSE(m.hit(tri, rt::ray{{-0.1f, 0.5f, 1}, {0, 0, -1}}, 0, 10, rec)); // x < 0
        CHECK_FALSE(m.hit(tri, rt::ray{{0.5f, -0.1f, 1}, {0, 0, -1}}, 0, 10, rec)); // y < 0
        CHECK_FALSE(m.hit(tri, rt::ray{{-1, 0.25f, 0}, {1, 0, 0}}, 0, 10, rec));    // in the plane
        CHECK_FALSE(m.hit(tri, rt::ray{{0.25f, 0.25f, -1}, {0, 0, -1}}, 0, 10, rec)); // t = -1

        // the interval [tmin, tmax] is closed
        CHECK_FALSE(m.hit(tri, rt::ray{{0.25f, 0.25f, 2}, {0, 0, -1}}, 0, real(1.5), rec));
        CHECK_FALSE(m.hit(tri, rt::ray{{0.25f, 0.25f, 2}, {0, 0, -1}}, real(2.5), 10, rec));
        CHECK(m.hit(tri, rt::ray{{0.25f, 0.25f, 2}, {0, 0, -1}}, 0, 2, rec));

        // a tilted triangle: a = (1,0,0), b = (0,2,0), c = (0,0,3) spans the plane
        // x + y/2 + z/3 = 1; the ray from 0 along (1,1,1) meets it at t = 6/11,
        // where x = b0, y = 2 b1, z = 3 b2: b0 = 6/11, b1 = 3/11, b2 = 2/11.
        const rt::triangle tilted{{1, 0, 0}, {0, 2, 0}, {0, 0, 3}, -1};
        REQUIRE(m.hit(tilted, rt::ray{{0, 0, 0}, {1, 1, 1}}, 0, 10, rec));
        CHECK(near(rec.t, real(6) / 11));
        CHECK(near(rec.b1, real(3) / 11));
        CHECK(near(rec.b2, real(2) / 11));
        CHECK(near(rec.point, vec3(real(6) / 11)));
        // (b - a) x (c - a) = (6, 3, 2) points away from the origin: the ray
        // from the origin meets the back
        CHECK_FALSE(rec.front_face);
        CHECK(near(rec.geometric_normal, -vec3(6, 3, 2) / real(7)));
    }
}

TEST_CASE("the hit point's error bound covers the point and shrinks with the coordinates")
{
    // point_error = gamma_7 (|b0 a| + |b1 b| + |b2 c|) (PBR 3rd ed., sec. 3.9.4)
    const rt::triangle tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, -1};
    rt::hit_record rec;
    REQUIRE(rt::hit_triangle(tri, rt::ray{{0.25f, 0.5f, 2}, {0, 0, -1}}, 0, 10, rec));
    CHECK(near(rec.point_error.x, rt::gamma_n(7) * real(0.25), real(1e-3)));
    CHECK(near(rec.point_error.y, rt::gamma_n(7) * real(0.5), real(1e-3)));
    CHECK(rec.point_error.z == 0);
    CHECK(rt::gamma_n(1) > rt::unit_roundoff);
    CHECK(rt::gamma_n(7) < 8 * rt::unit_roundoff);
}

TEST_CASE("a mesh interpolates the normals its file gives, turned to the side the ray came from")
{
    // corners with normals (0,0,1), (0,0,1), (1,0,0); at b = (0.25, 0.25, 0.5)
    // n = 0.5 (0,0,1) + 0.5 (1,0,0), normalised (1, 0, 1)/sqrt(2)
    rt::mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}};
    m.normals = {{0, 0, 1}, {1, 0, 0}};
    m.normal_indices = {{0, 0, 1}};
    m.face_materials = {3};
    const real h = real(1) / std::sqrt(real(2));
    rt::hit_record rec;
    REQUIRE(rt::hit_mesh(m, rt::ray{{0.25f, 0.5f, 1}, {0, 0, -1}}, 0, 10, rec));
    CHECK(near(rec.geometric_normal, vec3(0, 0, 1)));
    CHECK(near(rec.normal, vec3(h, 0, h)));
    CHECK(rec.material == 3);
    CHECK(rec.primitive == 0);
    REQUIRE(rt::hit_mesh(m, rt::ray{{0.25f, 0.5f, -1}, {0, 0, 1}}, 0, 10, rec));
    CHECK(near(rec.geometric_normal, vec3(0, 0, -1)));
    CHECK(near(rec.normal, vec3(-h, 0, -h)));

    // without normals (or with a corner missing one) the shading normal is the geometric one
    m.normal_indices = {{0, rt::no_index, 1}};
    REQUIRE(rt::hit_mesh(m, rt::ray{{0.25f, 0.5f, 1}, {0, 0, -1}}, 0, 10, rec));
    CHECK(near(rec.normal, vec3(0, 0, 1)));
}

// =============================================================================
// Closed meshes: watertight against Moller-Trumbore
// =============================================================================

TEST_CASE("rays from inside closed meshes at vertices and edges: Moller-Trumbore leaks, the watertight test never does")
{
    struct closed_mesh {
        const char* name;
        rt::mesh geometry;
        std::vector<vec3> inside;
    };
    const vec3 c(real(0.3), real(-0.7), real(0.2));
    const real r = real(1.7);
    std::vector<closed_mesh> meshes;
    meshes.push_back({"icosphere (3 subdivisions, 1280 triangles)", icosphere(3, c, r),
                      {c, c + r * vec3(0.3f, -0.2f, 0.1f), c + r * vec3(-0.45f, 0.35f, 0.3f)}});
    meshes.push_back({"cube.obj (12 triangles)", cube_from_file(),
                      {vec3(0), vec3(0.1f, 0.2f, -0.15f), vec3(-0.3f, 0.25f, 0.1f), vec3(0.37f, -0.41f, 0.29f)}});
    std::size_t total_mt_misses = 0;
    for (const closed_mesh& closed : meshes) {
        const std::string mesh_name = closed.name;
        CAPTURE(mesh_name);
        const rt::mesh& m = closed.geometry;
        const std::vector<surface_target> targets = vertex_and_edge_targets(m);
        const rt::scene s = scene_of(m);
        const rt::accelerator tree(s, rt::accelerator_kind::bvh);
        std::size_t rays = 0, mt_misses = 0, watertight_misses = 0, bvh_misses = 0, bvh_wrong_t = 0;
        for (const vec3& origin : closed.inside) {
            for (const surface_target& target : targets) {
                const rt::ray ray{origin, target.point - origin}; // reaches the target at t = 1
                ++rays;
                // A convex mesh is left exactly once, at the target: only the
                // triangles that the target lies on can be hit.
                bool mt = false, watertight = false;
                rt::hit_record rec;
                for (std::size_t i : target.triangles) {
                    const rt::index3& f = m.triangles[i];
                    const rt::triangle tri{m.positions[f[0]], m.positions[f[1]], m.positions[f[2]], -1};
                    mt = mt || rt::hit_triangle_moller_trumbore(tri, ray, 0, rt::infinity, rec);
                    watertight = watertight || rt::hit_triangle(tri, ray, 0, rt::infinity, rec);
                }
                mt_misses += mt ? 0 : 1;
                watertight_misses += watertight ? 0 : 1;
                if (!tree.closest_hit(ray, 0, rt::infinity, rec))
                    ++bvh_misses;
                else if (!near(rec.t, 1, real(1e-4)))
                    ++bvh_wrong_t;
            }
        }
        MESSAGE(mesh_name << ": " << rays << " rays, Moller-Trumbore misses " << mt_misses << " ("
                            << 100.0 * double(mt_misses) / double(rays) << "%), watertight misses "
                            << watertight_misses << ", BVH misses " << bvh_misses);
        CHECK(watertight_misses == 0);
        CHECK(bvh_misses == 0);
        CHECK(bvh_wrong_t == 0);
        total_mt_misses += mt_misses;
    }
    if (in_float)
        CHECK(total_mt_misses > 0); // the textbook method leaks in float
}

TEST_CASE("the SIMD leaf test and the scalar watertight test agree hit for hit, through shared edges and vertices")
{
    // The BVH tests its leaves four triangles at a time (rt::triangle_block,
    // rt::detail::intersect_block: SSE where available). Each lane must give
    // exactly what intersect_watertight gives for that triangle alone: the same
    // hit or miss, the same t and barycentrics, bit for bit. Rays from inside a
    // closed mesh at every vertex and along every edge (where the sign tests
    // decide), and random rays through it; the blocks are the mesh's triangles
    // four by four, the last one partial, and one block holds a sphere, which
    // the triangle test must leave alone.
    const vec3 c(real(0.3), real(-0.7), real(0.2));
    const real r = real(1.7);
    const rt::mesh m = icosphere(2, c, r);
    std::vector<rt::packed_primitive> prims;
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        const rt::index3& f = m.triangles[i];
        prims.push_back(rt::pack_triangle(m.positions[f[0]], m.positions[f[1]], m.positions[f[2]], std::uint32_t(i)));
    }
    rt::sphere ball;
    ball.center = c;
    ball.radius = r / 2;
    prims.insert(prims.begin() + 5, rt::pack_sphere(ball, 999)); // lane 1 of block 1
    REQUIRE(prims.size() % 4 == 1);                                 // the last block has one lane
    std::vector<rt::triangle_block> blocks;
    for (std::size_t first = 0; first < prims.size(); first += 4)
        blocks.push_back(rt::pack_triangle_block(prims.data(), first, std::min<std::size_t>(4, prims.size() - first)));
    REQUIRE(blocks.size() == (prims.size() + 3) / 4);

    std::vector<rt::ray> rays;
    const vec3 inside[] = {c, c + r * vec3(0.3f, -0.2f, 0.1f), c + r * vec3(-0.45f, 0.35f, 0.3f)};
    for (const vec3& origin : inside)
        for (const surface_target& target : vertex_and_edge_targets(m))
            rays.push_back(rt::ray{origin, target.point - origin});
    std::mt19937 random(17);
    std::uniform_real_distribution<real> unit(-1, 1);
    auto random_vec = [&] { // one number per statement: the same rays with every compiler
        vec3 v;
        v.x = unit(random);
        v.y = unit(random);
        v.z = unit(random);
        return v;
    };
    for (int k = 0; k < 3000; ++k) {
        const vec3 from = c + 3 * r * random_vec();
        const vec3 to = c + r * random_vec();
        rays.push_back(rt::ray{from, to - from});
    }

    std::size_t lane_tests = 0, hits = 0, disagreements = 0, rays_missing_the_mesh = 0;
    const std::size_t through_targets = rays.size() - 3000;
    for (std::size_t k = 0; k < rays.size(); ++k) {
        const rt::ray& ray = rays[k];
        const rt::watertight_ray w = rt::make_watertight_ray(ray);
        const rt::detail::leaf_ray leaf = rt::detail::make_leaf_ray(w);
        bool any = false;
        for (const real tmax : {rt::infinity, real(1)}) { // t = 1 is where the targets are
            for (const rt::triangle_block& b : blocks) {
                rt::triangle_hit simd[4];
                const int mask = rt::detail::intersect_block(b, leaf, w, 0, tmax, simd);
                for (int lane = 0; lane < 4; ++lane) {
                    ++lane_tests;
                    bool expected = false;
                    rt::triangle_hit scalar;
                    if (!(b.id[lane] & rt::sphere_flag)) {
                        real v[9];
                        for (int j = 0; j < 9; ++j)
                            v[j] = b.v[j][lane];
                        expected = rt::intersect_watertight(w, v, 0, tmax, scalar);
                    }
                    const bool got = (mask & (1 << lane)) != 0;
                    bool same = got == expected;
                    if (same && got) {
                        ++hits;
                        same = simd[lane].t == scalar.t && simd[lane].b0 == scalar.b0 && simd[lane].b1 == scalar.b1 &&
                               simd[lane].b2 == scalar.b2;
                    }
                    disagreements += same ? 0 : 1;
                    any = any || got;
                }
            }
        }
        if (k < through_targets && !any)
            ++rays_missing_the_mesh;
    }
    const std::string path = rt::bvh::uses_sse ? "SSE" : "the scalar fallback";
    MESSAGE("SIMD leaf test (" << path << "): " << rays.size() << " rays, "
                               << lane_tests << " lane tests, " << hits << " hits, " << disagreements
                               << " disagreements; rays at vertices and edges missing the closed mesh: "
                               << rays_missing_the_mesh);
    CHECK(hits > rays.size());
    CHECK(disagreements == 0);
    CHECK(rays_missing_the_mesh == 0);
}

// =============================================================================
// Rays spawned from hits (PBR 3rd ed., sec. 3.9.5)
// =============================================================================

TEST_CASE("a ray spawned from a hit never hits the same surface again at any scale, and naive starts do")
{
    // Rays from inside a closed mesh hit it; from each hit, new rays leave
    // inwards (like reflections) and outwards (like refractions). "Same
    // surface" is the triangle hit, or for the cube the face it belongs to
    // (each quad of cube.obj is two consecutive triangles).
    struct placement {
        const char* name;
        real scale;
        vec3 offset;
    };
    const placement placements[] = {{"unit size at the origin", 1, vec3(0)},
                                    {"a thousandth of the size", real(1e-3), vec3(0)},
                                    {"a thousand times larger", real(1e3), vec3(0)},
                                    {"moved 10^4 away", 1, vec3(1e4f, -2e4f, 5e3f)}};
    std::mt19937 random(7);
    std::uniform_real_distribution<real> uniform(-1, 1);
    auto random_unit = [&] {
        for (;;) {
            const vec3 v(uniform(random), uniform(random), uniform(random));
            const real l2 = glm::dot(v, v);
            if (l2 > real(0.01) && l2 <= 1)
                return v / std::sqrt(l2);
        }
    };
    std::size_t naive_total = 0, epsilon_total = 0;
    for (int shape = 0; shape < 2; ++shape) {
        for (const placement& place : placements) {
            const std::string shape_name = shape == 0 ? "icosphere" : "cube";
            const std::string place_name = place.name;
            CAPTURE(shape_name);
            CAPTURE(place_name);
            rt::mesh m = shape == 0 ? icosphere(2, vec3(0), 1) : cube_from_file();
            for (vec3& p : m.positions)
                p = p * place.scale + place.offset;
            const rt::scene s = scene_of(m);
            const rt::accelerator world(s, rt::accelerator_kind::bvh);
            auto same_surface = [&](std::uint32_t a, std::uint32_t b) { return shape == 0 ? a == b : a / 2 == b / 2; };
            std::size_t spawned = 0, library_rehits = 0, library_escapes = 0, library_hits_outward = 0;
            std::size_t naive_rehits = 0, epsilon_rehits = 0;
            for (int k = 0; k < 1500; ++k) {
                const vec3 from = place.offset + place.scale * real(0.2) * random_unit();
                const rt::ray primary{from, random_unit()};
                rt::hit_record rec;
                REQUIRE(world.closest_hit(primary, 0, rt::infinity, rec));
                // the geometric normal faces the ray, that is, into the mesh
                vec3 inward = random_unit();
                if (glm::dot(inward, rec.geometric_normal) < 0)
                    inward = -inward;
                const vec3 mirror = primary.direction - 2 * glm::dot(primary.direction, rec.geometric_normal) *
                                                            rec.geometric_normal;
                for (const vec3& w : {inward, mirror, -inward}) {
                    ++spawned;
                    const bool leaves_inward = glm::dot(w, rec.geometric_normal) > 0;
                    rt::hit_record next;
                    const bool hit = world.closest_hit(rt::spawn_ray(rec, w), 0, rt::infinity, next);
                    if (hit && same_surface(next.primitive, rec.primitive))
                        ++library_rehits;
                    if (leaves_inward && !hit)
                        ++library_escapes; // possible only within rounding of an edge: counted, not an error
                    if (!leaves_inward && hit)
                        ++library_hits_outward;  // nothing outside a convex mesh
                    // naive: start at p + t d with tmin = 0, or with a fixed epsilon
                    const rt::ray naive{primary.at(rec.t), w};
                    if (world.closest_hit(naive, 0, rt::infinity, next) && same_surface(next.primitive, rec.primitive))
                        ++naive_rehits;
                    if (world.closest_hit(naive, real(1e-4), rt::infinity, next) &&
                        same_surface(next.primitive, rec.primitive))
                        ++epsilon_rehits;
                }
            }
            MESSAGE(shape_name << ", " << place_name << ": " << spawned << " spawned rays; re-hits: spawn_ray "
                               << library_rehits << ", p + t d with tmin 0 " << naive_rehits
                               << ", p + t d with tmin 1e-4 " << epsilon_rehits << "; inward rays escaping "
                               << library_escapes);
            CHECK(library_rehits == 0);
            CHECK(library_hits_outward == 0);
            naive_total += naive_rehits;
            epsilon_total += epsilon_rehits;
        }
    }
    if (in_float) {
        CHECK(naive_total > 0);   // starting on the computed point re-hits
        CHECK(epsilon_total > 0); // a fixed epsilon is too small far from the origin
    }
}

TEST_CASE("a sliver just in front of a spawned ray blocks it, and the ray still does not hit its own triangle")
{
    // The distance check of the watertight test (PBR 3rd ed., sec. 3.9.6)
    // refuses a t within its rounding bound, which grows with the corners'
    // distances over |det|. For a sliver |det| is tiny and the bound can
    // exceed the true t: sponza-dabrovic.obj had such slivers, and shadow rays
    // went through them (docs/performance.md, experiment 6). Here a ray leaves
    // a floor (z = 0) straight up from (0, 0, 0), and a sliver 10.8 long and
    // 0.001 wide, tilted along x (its plane is z = 0.01 + 0.9 x), crosses it at
    // t = 0.01: U, V, W, det and T are those of the plane, worked out by hand.
    const rt::triangle floor{{-4, -4, 0}, {4, -4, 0}, {0, 4, 0}, -1};
    const rt::triangle sliver{{-5.4f, -0.0005f, 0.01f - 0.9f * 5.4f}, {5.4f, -0.0005f, 0.01f + 0.9f * 5.4f},
                              {0, 0.0005f, 0.01f}, -1};
    const vec3 origin = rt::offset_ray_origin(vec3(0), vec3(0, 0, 1));
    const rt::ray up{origin, {0, 0, 1}};
    const real t_true = real(0.01) - origin.z;

    // the float bound alone: with d = +z the shear is the identity (X = x, Y = y,
    // Z = z), so watertight_t_error gets the corners minus the origin directly
    if (in_float) {
        real x[3], y[3], z[3];
        const vec3 corners[3] = {sliver.a, sliver.b, sliver.c};
        for (int i = 0; i < 3; ++i) {
            x[i] = corners[i].x - origin.x;
            y[i] = corners[i].y - origin.y;
            z[i] = corners[i].z - origin.z;
        }
        const real U = x[2] * y[1] - y[2] * x[1], V = x[0] * y[2] - y[0] * x[2], W = x[1] * y[0] - y[1] * x[0];
        const real bound = rt::detail::watertight_t_error<real>(x, y, z, x, y, z, U, V, W, U + V + W);
        MESSAGE("sliver: t = " << t_true << ", float error bound of t = " << bound);
        CHECK(bound > t_true); // the float check alone refuses this hit
    }

    // the library: the hit at t = 0.01, whatever the path
    rt::hit_record rec;
    REQUIRE(rt::hit_triangle(sliver, up, 0, rt::infinity, rec));
    CHECK(near(rec.t, t_true, real(1e-4)));
    rt::scene s;
    s.shapes.emplace_back(floor);
    s.shapes.emplace_back(sliver);
    for (int k = 0; k < 20; ++k) // padding so that the BVH has inner nodes
        s.shapes.emplace_back(rt::triangle{{real(k), 10, 10}, {real(k) + 1, 10, 10}, {real(k), 11, 10}, -1});
    for (rt::accelerator_kind kind : {rt::accelerator_kind::flat, rt::accelerator_kind::bvh}) {
        const rt::accelerator world(s, kind);
        CHECK(world.any_hit(up, 0, 5));
        REQUIRE(world.closest_hit(up, 0, 5, rec));
        CHECK(rec.shape == 1);
        rt::primitive_hit scalar;
        if (kind == rt::accelerator_kind::bvh) {
            CHECK(world.tree().any_scalar(up, 0, 5));
            CHECK(world.tree().closest_scalar(up, 0, 5, scalar));
        }
    }

    // and the floor never hits itself: rays from offset points of the floor in
    // every upward direction, and straight along it
    std::mt19937 random(23);
    std::uniform_real_distribution<real> unit(-1, 1);
    std::size_t self_hits = 0;
    for (int k = 0; k < 2000; ++k) {
        vec3 p(0), d;
        p.x = unit(random); // one number per statement: the same rays with every compiler
        p.y = unit(random);
        d.x = unit(random);
        d.y = unit(random);
        d.z = unit(random);
        const vec3 start = rt::offset_ray_origin(p, vec3(0, 0, 1));
        d.z = k % 10 == 0 ? real(1e-7) : std::fabs(d.z);
        if (glm::dot(d, d) == 0)
            d = vec3(0, 0, 1);
        self_hits += rt::hit_triangle(floor, rt::ray{start, d}, 0, rt::infinity, rec) ? 1 : 0;
    }
    CHECK(self_hits == 0);
}

TEST_CASE("a ray spawned from a sphere hit does not hit the sphere again on its way out")
{
    // From inside a sphere every hit is on the far side; a ray spawned outwards
    // crosses the surface it starts on and must hit nothing.
    std::mt19937 random(9);
    std::uniform_real_distribution<real> uniform(-1, 1);
    auto random_unit = [&] {
        for (;;) {
            const vec3 v(uniform(random), uniform(random), uniform(random));
            const real l2 = glm::dot(v, v);
            if (l2 > real(0.01) && l2 <= 1)
                return v / std::sqrt(l2);
        }
    };
    std::size_t spawn_total = 0, naive_total = 0;
    for (real radius : {real(1e-3), real(1), real(1e3)}) {
        for (const vec3& center : {vec3(0), vec3(1e4f, -3e3f, 2e3f)}) {
            rt::scene s;
            rt::sphere ball;
            ball.center = center;
            ball.radius = radius;
            s.shapes.emplace_back(ball);
            const rt::accelerator world(s);
            std::size_t spawned = 0, rehits = 0, naive_rehits = 0;
            for (int k = 0; k < 1000; ++k) {
                const rt::ray primary{center + radius * real(0.3) * random_unit(), random_unit()};
                rt::hit_record rec, next;
                REQUIRE(world.closest_hit(primary, 0, rt::infinity, rec));
                vec3 outward = random_unit();
                if (glm::dot(outward, rec.geometric_normal) > 0)
                    outward = -outward;
                ++spawned;
                rehits += world.closest_hit(rt::spawn_ray(rec, outward), 0, rt::infinity, next) ? 1 : 0;
                naive_rehits += world.closest_hit(rt::ray{primary.at(rec.t), outward}, 0, rt::infinity, next) ? 1 : 0;
            }
            MESSAGE("sphere of radius " << radius << " at " << center.x << ": " << spawned
                                        << " outward rays, re-hits: spawn_ray " << rehits << ", p + t d " << naive_rehits);
            CHECK(rehits == 0);
            spawn_total += rehits;
            naive_total += naive_rehits;
        }
    }
    CHECK(spawn_total == 0);
    if (in_float)
        CHECK(naive_total > 0);
}

// =============================================================================
// The slab test (Williams et al. 2005, Ize 2013)
// =============================================================================

TEST_CASE("the slab test handles axis-parallel rays, rays in a slab plane, -0 and flat boxes without NaN")
{
    rt::aabb box;
    box.lo = vec3(-1, -1, -1);
    box.hi = vec3(1, 2, 3);
    const real zero = 0, minus_zero = -real(0);
    real tnear = -1;
    auto hits = [&](const vec3& o, const vec3& d, real tmin = 0, real tmax = rt::infinity) {
        tnear = std::numeric_limits<real>::quiet_NaN();
        const bool hit = rt::hit_box(box, rt::make_box_ray(rt::ray{o, d}), tmin, tmax, tnear);
        CHECK_FALSE(std::isnan(tnear));
        return hit;
    };
    // axis-parallel, through the box, and beside it
    CHECK(hits({-5, 0, 0}, {1, zero, zero}));
    CHECK(tnear == 4);
    CHECK_FALSE(hits({-5, 2.5f, 0}, {1, zero, zero}));
    CHECK_FALSE(hits({-5, 0, 0}, {-1, zero, zero})); // pointing away
    // in a slab plane (origin on the plane, direction inside it): the box is closed
    CHECK(hits({-5, 2, 0}, {1, zero, zero}));
    CHECK(tnear == 4);
    CHECK(hits({-5, -1, 0}, {1, zero, zero}));
    CHECK(hits({-5, 2, 0}, {1, minus_zero, zero}));
    CHECK(hits({-5, -1, 0}, {1, minus_zero, minus_zero}));
    CHECK(hits({-5, 2, 3}, {1, minus_zero, zero})); // along an edge
    CHECK(hits({1, 2, 3}, {minus_zero, minus_zero, -1})); // down an edge from a corner
    CHECK(tnear == 0);
    // just outside a plane, parallel to it: a miss
    CHECK_FALSE(hits({-5, std::nextafter(real(2), real(3)), 0}, {1, zero, zero}));
    CHECK_FALSE(hits({-5, std::nextafter(real(-1), real(-2)), 0}, {1, minus_zero, zero}));
    // a flat box (lo = hi on y), met only in its plane or across it
    box.lo.y = box.hi.y = real(0.5);
    CHECK(hits({-5, 0.5f, 0}, {1, zero, zero}));
    CHECK(hits({0, 5, 0}, {zero, -1, zero}));
    CHECK(tnear == real(4.5));
    CHECK_FALSE(hits({-5, 0.6f, 0}, {1, zero, zero}));
    // the interval: an origin inside enters at tmin; tmax before the box, tmin after it
    box.lo = vec3(-1);
    box.hi = vec3(1);
    CHECK(hits({0, 0, 0}, {1, 1, 1}, real(0.25)));
    CHECK(tnear == real(0.25));
    CHECK_FALSE(hits({-5, 0, 0}, {1, 0, 0}, 0, 3));
    CHECK_FALSE(hits({-5, 0, 0}, {1, 0, 0}, 7));
    // the empty box (lo = +inf, hi = -inf) is met by nothing
    box = rt::aabb{};
    CHECK_FALSE(hits({0, 0, 0}, {1, 0, 0}));
    CHECK_FALSE(hits({0, 0, 0}, {zero, minus_zero, 1}));
}

TEST_CASE("without Ize's factor the slab test culls boxes that a ray touches at an edge, with it never")
{
    // The ray passes exactly through the edge x = 1, y = 0 of the box [0,1]^3
    // (at z = 1/2): it leaves the x slab where it enters the y slab, so the exact
    // t_near equals t_far. Directions with integer components a, b, c and the
    // origin P - s d make everything exact except the rounded 1/d.
    rt::aabb box;
    box.lo = vec3(0);
    box.hi = vec3(1);
    std::size_t rays = 0, culled_plain = 0, culled_ize = 0;
    for (int a = 1; a <= 31; ++a)
        for (int b = 1; b <= 31; ++b)
            for (int c = -3; c <= 3; ++c)
                for (int s = 1; s <= 5; ++s) {
                    const vec3 d{real(a), real(b), real(c)};
                    const vec3 o = vec3(1, 0, 0.5f) - real(s) * d;
                    const rt::box_ray r = rt::make_box_ray(rt::ray{o, d});
                    real tnear = 0;
                    ++rays;
                    culled_plain += rt::hit_box(box, r, 0, rt::infinity, tnear, 1) ? 0 : 1;
                    culled_ize += rt::hit_box(box, r, 0, rt::infinity, tnear) ? 0 : 1;
                }
    MESSAGE(rays << " rays through a box edge: culled without the factor " << culled_plain
                 << ", with 1 + 2 gamma_3 " << culled_ize);
    CHECK(culled_ize == 0);
    if (in_float)
        CHECK(culled_plain > 0); // in double these rays happen to round the same on both planes

}

// =============================================================================
// The BVH against the list
// =============================================================================

namespace {

/// A random scene: spheres, single triangles (some sharing edges, in a grid)
/// and meshes, as asked.
rt::scene random_scene(std::mt19937& random, int spheres, int triangles, bool meshes)
{
    std::uniform_real_distribution<real> pos(-5, 5), size(real(0.05), 1), unit(-1, 1);
    rt::scene s;
    for (int k = 0; k < spheres; ++k) {
        rt::sphere ball;
        ball.center = vec3(pos(random), pos(random), pos(random));
        ball.radius = size(random);
        ball.material = k % 3;
        s.shapes.emplace_back(ball);
        if (k % 5 == 0 && triangles > 0) { // interleave kinds in the shape list
            const vec3 c(pos(random), pos(random), pos(random));
            s.shapes.emplace_back(rt::triangle{c, c + vec3(unit(random), unit(random), unit(random)),
                                               c + vec3(unit(random), unit(random), unit(random)), 1});
            --triangles;
        }
    }
    for (int k = 0; k < triangles; ++k) {
        if (k < 64) { // an 8 x 4 grid of squares as separate triangles, sharing edges and corners
            const real x = real(k % 8) - 4, y = real(k / 8) - 2;
            const vec3 p00(x, y, 0), p10(x + 1, y, 0), p01(x, y + 1, 0), p11(x + 1, y + 1, 0);
            s.shapes.emplace_back(k % 2 == 0 ? rt::triangle{p00, p10, p11, 2} : rt::triangle{p00, p11, p01, 2});
            continue;
        }
        const vec3 c(pos(random), pos(random), pos(random));
        const real r = size(random);
        s.shapes.emplace_back(rt::triangle{c + r * vec3(unit(random), unit(random), unit(random)),
                                           c + r * vec3(unit(random), unit(random), unit(random)),
                                           c + r * vec3(unit(random), unit(random), unit(random)), -1});
    }
    if (meshes) {
        s.shapes.emplace_back(icosphere(2, vec3(1, 1.5f, -2), real(1.2)));
        rt::mesh box = cube_from_file();
        for (vec3& p : box.positions)
            p = p * real(2) + vec3(-2, 1, 2);
        box.face_materials.assign(box.triangles.size(), 1);
        s.shapes.emplace_back(std::move(box));
    }
    return s;
}

/// Random rays through the scene's region, some with unit, some with long or
/// short directions, some axis-parallel (with -0) and some aimed at grid corners.
std::vector<rt::ray> random_rays(std::mt19937& random, int count)
{
    std::uniform_real_distribution<real> pos(-7, 7), unit(-1, 1);
    std::vector<rt::ray> rays;
    for (int k = 0; k < count; ++k) {
        rt::ray r;
        r.origin = vec3(pos(random), pos(random), pos(random));
        switch (k % 5) {
        case 0:
            r.direction = glm::normalize(vec3(unit(random), unit(random), unit(random)));
            break;
        case 1:
            r.direction = vec3(unit(random), unit(random), unit(random)) * real(37);
            break;
        case 2: { // axis-parallel, any sign of zero
            const int axis = k % 3;
            r.direction = vec3(k % 7 < 3 ? real(0) : -real(0));
            r.direction[axis] = unit(random) < 0 ? -1 : 1;
            break;
        }
        case 3: { // at a corner of the grid
            const vec3 corner(real(k % 9) - 4, real(k % 5) - 2, 0);
            r.direction = corner - r.origin;
            break;
        }
        default:
            r.direction = vec3(unit(random), unit(random), unit(random)) * real(0.01);
        }
        if (glm::dot(r.direction, r.direction) == 0)
            r.direction = vec3(1, 0, 0);
        rays.push_back(r);
    }
    return rays;
}

bool same_hit(const rt::hit_record& a, const rt::hit_record& b)
{
    return a.t == b.t && a.shape == b.shape && a.primitive == b.primitive && a.material == b.material &&
           a.point == b.point && a.normal == b.normal && a.geometric_normal == b.geometric_normal &&
           a.front_face == b.front_face && a.b1 == b.b1 && a.b2 == b.b2 && a.point_error == b.point_error;
}

} // namespace

TEST_CASE("the BVH and the list return the same closest hit and the same any-hit answer on random scenes")
{
    std::mt19937 random(2024);
    struct setup {
        const char* name;
        int spheres, triangles;
        bool meshes;
    };
    const setup setups[] = {{"spheres only", 300, 0, false},
                            {"triangles only", 0, 600, true},
                            {"spheres, triangles and meshes", 150, 300, true}};
    for (const setup& kind : setups) {
        const std::string kind_name = kind.name;
        CAPTURE(kind_name);
        const rt::scene s = random_scene(random, kind.spheres, kind.triangles, kind.meshes);
        const rt::accelerator flat(s, rt::accelerator_kind::flat);
        const rt::accelerator tree(s, rt::accelerator_kind::bvh);
        REQUIRE(flat.kind() == rt::accelerator_kind::flat);
        REQUIRE(tree.kind() == rt::accelerator_kind::bvh);
        REQUIRE(tree.stats().nodes > 1);
        std::size_t hits = 0, disagreements = 0, any_disagreements = 0;
        const std::vector<rt::ray> rays = random_rays(random, 1500);
        for (const rt::ray& r : rays) {
            rt::hit_record from_list, from_flat, from_tree;
            const bool list_hit = rt::closest_hit_list(s, r, 0, rt::infinity, from_list);
            const bool flat_hit = flat.closest_hit(r, 0, rt::infinity, from_flat);
            const bool tree_hit = tree.closest_hit(r, 0, rt::infinity, from_tree);
            rt::primitive_hit scalar_hit, simd_hit;
            const bool tree_scalar = tree.tree().closest_scalar(r, 0, rt::infinity, scalar_hit);
            const bool tree_simd = tree.tree().closest(r, 0, rt::infinity, simd_hit);
            bool agree = list_hit == flat_hit && list_hit == tree_hit && tree_scalar == tree_simd &&
                         tree.tree().any_scalar(r, 0, rt::infinity) == tree.tree().any(r, 0, rt::infinity);
            if (agree && list_hit) {
                ++hits;
                agree = same_hit(from_list, from_flat) && same_hit(from_list, from_tree) &&
                        scalar_hit.t == simd_hit.t && scalar_hit.id == simd_hit.id;
            }
            disagreements += agree ? 0 : 1;
            // any hit, with tmax a little before and a little beyond the closest
            // hit (not at its computed t: there the answer depends on rounding,
            // see docs/stages/04-triangle.md) and at infinity
            const real before = list_hit ? from_list.t * (1 - real(1) / 1024) : real(1);
            const real beyond = list_hit ? from_list.t * (1 + real(1) / 1024) : real(10);
            for (real tmax : {before, beyond, rt::infinity}) {
                const bool expected = list_hit && from_list.t <= tmax;
                const bool answers[] = {rt::any_hit_list(s, r, 0, tmax), flat.any_hit(r, 0, tmax),
                                        tree.any_hit(r, 0, tmax)};
                for (bool answer : answers)
                    any_disagreements += answer == expected ? 0 : 1;
            }
        }
        MESSAGE(kind_name << ": " << s.shapes.size() << " shapes, " << tree.primitive_count() << " primitives, "
                          << rays.size() << " rays, " << hits << " hits, " << disagreements
                          << " disagreements, any-hit disagreements " << any_disagreements);
        CHECK(hits > rays.size() / 10);
        CHECK(disagreements == 0);
        CHECK(any_disagreements == 0);
    }
}

TEST_CASE("the closest hit of the list: the nearest shape, its index, and at an equal t the later shape")
{
    rt::scene s;
    rt::sphere far_ball, near_ball;
    far_ball.center = vec3(0, 0, -10);
    far_ball.material = 1;
    near_ball.center = vec3(0, 0, -5);
    near_ball.material = 2;
    s.shapes.emplace_back(far_ball);
    s.shapes.emplace_back(near_ball);
    // two identical triangles at z = -2: the same t, so the later one is kept
    s.shapes.emplace_back(rt::triangle{{-1, -1, -2}, {1, -1, -2}, {0, 1, -2}, 3});
    s.shapes.emplace_back(rt::triangle{{-1, -1, -2}, {1, -1, -2}, {0, 1, -2}, 4});
    const rt::ray down_z{{0, 0, 0}, {0, 0, -1}};
    rt::hit_record rec;
    REQUIRE(rt::closest_hit_list(s, down_z, 0, rt::infinity, rec));
    CHECK(rec.shape == 3);
    CHECK(rec.material == 4);
    CHECK(near(rec.t, 2));
    // beyond the triangles: the near sphere, whose surface is at z = -4
    REQUIRE(rt::closest_hit_list(s, down_z, 3, rt::infinity, rec));
    CHECK(rec.shape == 1);
    CHECK(near(rec.t, 4));
    CHECK(rec.material == 2);
    CHECK(near(rec.point, vec3(0, 0, -4)));
    CHECK(near(rec.geometric_normal, vec3(0, 0, 1)));
    // a tmax before everything: no hit
    CHECK_FALSE(rt::closest_hit_list(s, down_z, 0, real(1.5), rec));
    CHECK_FALSE(rt::any_hit_list(s, down_z, 0, real(1.5)));
    // the accelerators follow the same rule
    for (rt::accelerator_kind kind : {rt::accelerator_kind::flat, rt::accelerator_kind::bvh}) {
        const rt::accelerator world(s, kind);
        REQUIRE(world.closest_hit(down_z, 0, rt::infinity, rec));
        CHECK(rec.shape == 3);
        CHECK(world.any_hit(down_z, 0, 3));
        CHECK_FALSE(world.any_hit(down_z, 0, real(1.5)));
    }
}

TEST_CASE("many copies of one triangle: the BVH still builds and keeps the last copy, as the list does")
{
    // every centroid is the same point, so no plane separates them
    rt::mesh m;
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    for (int k = 0; k < 1000; ++k)
        m.triangles.push_back({0, 1, 2});
    const rt::scene s = scene_of(m);
    const rt::accelerator tree(s, rt::accelerator_kind::bvh);
    CHECK(tree.stats().depth < rt::bvh::max_depth + 2);
    rt::hit_record rec;
    REQUIRE(tree.closest_hit(rt::ray{{0, 0, 3}, {0, 0, -1}}, 0, rt::infinity, rec));
    CHECK(rec.primitive == 999);
    REQUIRE(rt::closest_hit_list(s, rt::ray{{0, 0, 3}, {0, 0, -1}}, 0, rt::infinity, rec));
    CHECK(rec.primitive == 999);
}

TEST_CASE("the BVH is the same whatever the number of threads that build it")
{
    std::mt19937 random(5);
    const rt::scene s = random_scene(random, 2000, 6000, true); // large enough to be split among threads
    for (const bool spatial : {false, true}) {
        CAPTURE(spatial);
        rt::bvh_options one, four;
        one.threads = 1;
        four.threads = 4;
        if (spatial) { // forced everywhere, so that the threads share the top of the tree
            one.spatial_budget = four.spatial_budget = 1;
            one.spatial_overlap = four.spatial_overlap = 0;
        } else {
            one.spatial_budget = four.spatial_budget = 0;
        }
        const rt::accelerator a(s, rt::accelerator_kind::bvh, one), b(s, rt::accelerator_kind::bvh, four);
        CHECK((a.stats().spatial_splits > 0) == spatial);
        const std::vector<rt::bvh_node>& na = a.tree().nodes();
        const std::vector<rt::bvh_node>& nb = b.tree().nodes();
        REQUIRE(na.size() == nb.size());
        bool same = true;
        for (std::size_t i = 0; i < na.size(); ++i)
            for (int c = 0; c < 4; ++c) {
                same = same && na[i].child[c] == nb[i].child[c] && na[i].count[c] == nb[i].count[c];
                for (int row = 0; row < 6; ++row)
                    same = same && na[i].bounds[row][c] == nb[i].bounds[row][c];
            }
        const std::vector<rt::packed_primitive>& pa = a.tree().primitives();
        const std::vector<rt::packed_primitive>& pb = b.tree().primitives();
        REQUIRE(pa.size() == pb.size());
        for (std::size_t i = 0; i < pa.size(); ++i)
            same = same && pa[i].id == pb[i].id;
        CHECK(same);
        CHECK(a.stats().nodes == b.stats().nodes);
        CHECK(a.stats().depth == b.stats().depth);
        CHECK(a.stats().references == b.stats().references);
    }
}

TEST_CASE("a spatial split's piece holds its part of the triangle: clipped_box never cuts it")
{
    // Random triangles, random planes through them, points of the triangle
    // (corners, points on the edges, inside) computed in double: each point
    // on a side of the plane lies in that side's box, also when the box is
    // cut to a smaller one that holds the point (the piece a node already has).
    std::mt19937 random(17);
    std::uniform_real_distribution<double> coordinate(-1000, 1000), unit(0, 1);
    std::size_t points = 0, outside = 0;
    for (int k = 0; k < 2000; ++k) {
        const double scale = std::pow(10.0, double(k % 7) - 3); // 1e-3 ... 1e3
        vec3 corner[3];
        for (vec3& c : corner)
            c = vec3(real(scale * coordinate(random)), real(scale * coordinate(random)), real(scale * coordinate(random)));
        const rt::packed_primitive p = rt::pack_triangle(corner[0], corner[1], corner[2], 0);
        const rt::aabb box = rt::packed_bounds(p);
        const int axis = k % 3;
        const real s = box.lo[axis] + real(unit(random)) * (box.hi[axis] - box.lo[axis]);
        const rt::aabb below = rt::detail::clipped_box(p, axis, s, true, box);
        const rt::aabb above = rt::detail::clipped_box(p, axis, s, false, box);
        for (int j = 0; j < 64; ++j) {
            double b1 = unit(random), b2 = unit(random);
            if (b1 + b2 > 1) {
                b1 = 1 - b1;
                b2 = 1 - b2;
            }
            if (j % 4 == 1) // on an edge
                b2 = 0;
            if (j % 4 == 2)
                b2 = 1 - b1;
            if (j == 3) // a corner
                b1 = b2 = 0;
            double q[3];
            for (int i = 0; i < 3; ++i)
                q[i] = (1 - b1 - b2) * double(corner[0][i]) + b1 * double(corner[1][i]) + b2 * double(corner[2][i]);
            for (const bool side_below : {true, false}) {
                if (side_below ? q[axis] > double(s) : q[axis] < double(s))
                    continue;
                const rt::aabb& piece = side_below ? below : above;
                ++points;
                bool in = true;
                for (int i = 0; i < 3; ++i)
                    in = in && double(piece.lo[i]) <= q[i] && q[i] <= double(piece.hi[i]);
                outside += in ? 0 : 1;
            }
        }
    }
    MESSAGE(points << " points of 2000 cut triangles, " << outside << " outside their piece's box");
    CHECK(points > 100000);
    CHECK(outside == 0);
}

TEST_CASE("a BVH with spatial splits: every ray through a closed mesh's edges and vertices hits, and hits as the list")
{
    // An icosphere stretched 40 times along a diagonal: long thin slanted
    // triangles whose boxes overlap, the case spatial splits are for. Forced
    // on everywhere (no overlap threshold, one extra reference per triangle).
    rt::mesh m = icosphere(3, vec3(0), 1);
    const vec3 d = glm::normalize(vec3(1, 1, real(0.5)));
    for (vec3& v : m.positions)
        v += real(39) * glm::dot(v, d) * d;
    const rt::scene s = scene_of(m);
    rt::bvh_options cut;
    cut.spatial_budget = 1;
    cut.spatial_overlap = 0;
    rt::bvh_options plain;
    plain.spatial_budget = 0;
    const rt::accelerator tree(s, rt::accelerator_kind::bvh, cut);
    const rt::accelerator uncut(s, rt::accelerator_kind::bvh, plain);
    MESSAGE(m.triangles.size() << " triangles, " << tree.stats().references << " references after "
                               << tree.stats().spatial_splits << " spatial splits; SAH cost "
                               << tree.stats().sah_cost << " (without: " << uncut.stats().sah_cost << ")");
    REQUIRE(tree.stats().spatial_splits > 0);
    REQUIRE(tree.stats().references > m.triangles.size());
    CHECK(uncut.stats().spatial_splits == 0);
    CHECK(uncut.stats().references == m.triangles.size());
    CHECK(tree.stats().sah_cost < uncut.stats().sah_cost); // what the splits were taken for

    const std::vector<surface_target> targets = vertex_and_edge_targets(m);
    std::size_t rays = 0, misses = 0, wrong_t = 0;
    for (const vec3& origin : {vec3(0), real(13) * d + vec3(real(0.2), real(-0.1), 0), real(-31) * d + vec3(0, real(0.1), real(-0.05))}) {
        for (const surface_target& target : targets) {
            const rt::ray ray{origin, target.point - origin};
            ++rays;
            rt::hit_record rec;
            if (!tree.closest_hit(ray, 0, rt::infinity, rec))
                ++misses;
            else if (!near(rec.t, 1, real(1e-4)))
                ++wrong_t;
            misses += tree.any_hit(ray, 0, rt::infinity) ? 0 : 1;
        }
    }
    MESSAGE(rays << " rays through edges and vertices from inside: " << misses << " misses");
    CHECK(misses == 0);
    CHECK(wrong_t == 0);

    // random rays: the same hit as the list, bit for bit
    std::mt19937 random(23);
    std::size_t hits = 0, disagreements = 0;
    for (const rt::ray& r : random_rays(random, 3000)) {
        rt::hit_record a, b;
        const bool in_list = rt::closest_hit_list(s, r, 0, rt::infinity, a);
        const bool in_tree = tree.closest_hit(r, 0, rt::infinity, b);
        disagreements += in_list == in_tree && (!in_list || same_hit(a, b)) &&
                                 rt::any_hit_list(s, r, 0, rt::infinity) == tree.any_hit(r, 0, rt::infinity)
                             ? 0
                             : 1;
        hits += in_list ? 1 : 0;
    }
    MESSAGE("3000 random rays: " << hits << " hits, " << disagreements << " disagreements with the list");
    CHECK(hits > 100);
    CHECK(disagreements == 0);
}

TEST_CASE("an accelerator of an empty scene or of one shape, and auto picks the flat list for tiny scenes")
{
    const rt::scene empty;
    const rt::accelerator none(empty);
    rt::hit_record rec;
    CHECK_FALSE(none.closest_hit(rt::ray{{0, 0, 0}, {1, 0, 0}}, 0, rt::infinity, rec));
    CHECK_FALSE(none.any_hit(rt::ray{{0, 0, 0}, {1, 0, 0}}, 0, rt::infinity));
    const rt::accelerator empty_tree(empty, rt::accelerator_kind::bvh);
    CHECK_FALSE(empty_tree.closest_hit(rt::ray{{0, 0, 0}, {1, 0, 0}}, 0, rt::infinity, rec));

    rt::scene one;
    rt::sphere ball;
    ball.center = vec3(5, 0, 0);
    one.shapes.emplace_back(ball);
    const rt::accelerator automatic(one);
    CHECK(automatic.kind() == rt::accelerator_kind::flat);
    const rt::accelerator tree(one, rt::accelerator_kind::bvh);
    REQUIRE(tree.closest_hit(rt::ray{{0, 0, 0}, {1, 0, 0}}, 0, rt::infinity, rec));
    CHECK(near(rec.t, 4));
    CHECK(tree.any_hit(rt::ray{{0, 0, 0}, {1, 0, 0}}, 0, rt::infinity));
    CHECK_FALSE(tree.any_hit(rt::ray{{0, 0, 0}, {-1, 0, 0}}, 0, rt::infinity));

    std::mt19937 random(3);
    const rt::scene many = random_scene(random, 0, 200, false);
    CHECK(rt::accelerator(many).kind() == rt::accelerator_kind::bvh);

    CHECK(rt::parse_accelerator_kind("auto") == rt::accelerator_kind::automatic);
    CHECK(rt::parse_accelerator_kind("flat") == rt::accelerator_kind::flat);
    CHECK(rt::parse_accelerator_kind("bvh") == rt::accelerator_kind::bvh);
    CHECK_THROWS_AS(rt::parse_accelerator_kind("kd-tree"), rt::error);
}

TEST_CASE("the BVH agrees hit for hit with the flat list on the Stanford bunny")
{
    const std::filesystem::path bunny = std::filesystem::path(RT_SHARED_DIR) / "meshes" / "stanford-bunny.obj";
    if (!std::filesystem::exists(bunny)) {
        MESSAGE("skipped: " << bunny.string() << " is not there");
        return;
    }
    const rt::scene s = scene_of(rt::load_obj(bunny).geometry);
    const rt::mesh& m = std::get<rt::mesh>(s.shapes[0]);
    REQUIRE(m.triangles.size() == 69451);
    const rt::accelerator flat(s, rt::accelerator_kind::flat);
    const rt::accelerator tree(s, rt::accelerator_kind::bvh);
    const rt::aabb box = bounds_of(m);
    std::mt19937 random(11);
    std::uniform_real_distribution<real> unit(0, 1);
    std::size_t hits = 0, disagreements = 0;
    const int rays = 120; // the flat list tests all 69451 triangles per ray
    for (int k = 0; k < rays; ++k) {
        // from a point around the bunny to a random point in its box
        const vec3 target = box.lo + vec3(unit(random), unit(random), unit(random)) * box.extent();
        const vec3 from = box.center() + glm::length(box.extent()) *
                                             glm::normalize(vec3(unit(random) - real(0.5), unit(random) - real(0.5),
                                                                 unit(random) - real(0.5)));
        const rt::ray r{from, target - from};
        rt::hit_record a, b;
        const bool hit_flat = flat.closest_hit(r, 0, rt::infinity, a);
        const bool hit_tree = tree.closest_hit(r, 0, rt::infinity, b);
        const bool same = hit_flat == hit_tree && (!hit_flat || same_hit(a, b)) &&
                          flat.any_hit(r, 0, rt::infinity) == tree.any_hit(r, 0, rt::infinity);
        disagreements += same ? 0 : 1;
        hits += hit_flat ? 1 : 0;
    }
    MESSAGE("bunny: " << rays << " rays, " << hits << " hits, " << disagreements << " disagreements");
    CHECK(hits > rays / 4);
    CHECK(disagreements == 0);
}

// =============================================================================
// OBJ files
// =============================================================================

TEST_CASE("an OBJ mesh keeps only what its file gives")
{
    const rt::obj_result cube = rt::load_obj(RT_TEST_DATA_DIR "/cube.obj");
    CHECK(cube.geometry.positions.size() == 8);
    CHECK(cube.geometry.triangles.size() == 12); // six quads
    CHECK(cube.polygons == 6);
    CHECK(cube.geometry.normals.empty());
    CHECK(cube.geometry.normal_indices.empty());
    CHECK(cube.geometry.texcoords.empty());
    CHECK(cube.geometry.face_materials.empty());
    CHECK(cube.materials.empty());
    CHECK(cube.geometry.dropped_degenerate == 0);

    const std::filesystem::path folder = scratch_folder("kept");
    // normals and texture coordinates given and used
    rt::obj_result with = rt::load_obj(write_file(folder / "with.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                                        "vn 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                                                        "f 1/1/1 2/2/1 3/3/1\n"));
    CHECK(with.geometry.normals.size() == 1);
    REQUIRE(with.geometry.normal_indices.size() == 1);
    CHECK(with.geometry.normal_indices[0] == rt::index3{0, 0, 0});
    CHECK(with.geometry.texcoords.size() == 3);
    REQUIRE(with.geometry.texcoord_indices.size() == 1);
    CHECK(with.geometry.texcoord_indices[0] == rt::index3{0, 1, 2});
    // given but not used by any face: not kept
    rt::obj_result unused = rt::load_obj(write_file(folder / "unused.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                                            "vn 0 0 1\nvt 0 0\nf 1 2 3\n"));
    CHECK(unused.geometry.normals.empty());
    CHECK(unused.geometry.texcoords.empty());
    // only normals, in the v//vn form
    rt::obj_result normals_only =
        rt::load_obj(write_file(folder / "normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n"));
    CHECK(normals_only.geometry.normals.size() == 1);
    CHECK(normals_only.geometry.texcoords.empty());
}

TEST_CASE("OBJ faces: negative indices count back, polygons are triangulated, zero-area triangles are dropped and counted")
{
    const std::filesystem::path folder = scratch_folder("faces");
    // -1 is the latest vertex so far: "f -3 -2 -1" after three v lines is "f 1 2 3"
    rt::obj_result relative = rt::load_obj(write_file(folder / "relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                                                "f -3 -2 -1\n"
                                                                                "v 0 0 1\nf -4 -3 -1\n"));
    REQUIRE(relative.geometry.triangles.size() == 2);
    CHECK(relative.geometry.triangles[0] == rt::index3{0, 1, 2});
    CHECK(relative.geometry.triangles[1] == rt::index3{0, 1, 3});
    // a quad gives 2 triangles, a (convex) pentagon 3
    rt::obj_result polygons = rt::load_obj(write_file(folder / "polygons.obj", "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
                                                                                "v 3 0.5 0\nf 1 2 3 4\nf 1 2 5 3 4\n"));
    CHECK(polygons.polygons == 2);
    CHECK(polygons.geometry.triangles.size() == 5);
    // a repeated corner and three corners on a line have no area
    rt::obj_result degenerate = rt::load_obj(write_file(folder / "degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
                                                                                    "f 1 2 3\nf 1 1 2\nf 1 2 4\n"));
    CHECK(degenerate.geometry.triangles.size() == 1);
    CHECK(degenerate.geometry.dropped_degenerate == 2);
    CHECK(rt::summary(degenerate).find("2 degenerate triangles dropped") != std::string::npos);
}

TEST_CASE("MTL colours become rt materials, per face")
{
    const std::filesystem::path folder = scratch_folder("mtl");
    write_file(folder / "colours.mtl", "# two materials\n"
                                       "newmtl red\nKa 0.1 0.2 0.3\nKd 0.8 0.1 0.1   # inline comment\n"
                                       "Ks 0.5 0.5 0.5\nNs 64\nillum 2\n"
                                       "newmtl mirror\nKd 0.5\nKs 0.9 0.9 0.9\nillum 3\nKe 1 1 1\nmap_Kd wood.png\n");
    const rt::obj_result loaded = rt::load_obj(write_file(folder / "coloured.obj", "mtllib colours.mtl\n"
                                                                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                                                                   "f 1 2 3\nusemtl red\nf 2 4 3\n"
                                                                                   "usemtl mirror\nf 1 2 4\n"));
    REQUIRE(loaded.materials.size() == 2);
    const rt::material& red = loaded.materials[0];
    CHECK(red.name == "red");
    CHECK(red.ka == rt::color(0.1f, 0.2f, 0.3f));
    CHECK(red.kd == rt::color(0.8f, 0.1f, 0.1f));
    CHECK(red.ks == rt::color(0.5f));
    CHECK(red.p == 64);
    CHECK(red.km == rt::color(0.0f)); // illum 2: no reflection
    const rt::material& mirror = loaded.materials[1];
    CHECK(mirror.kd == rt::color(0.5f)); // "Kd r" is r r r
    CHECK(mirror.ka == mirror.kd);       // no Ka: as in scene files
    CHECK(mirror.p == rt::material{}.p); // no Ns: the default exponent
    CHECK(mirror.km == rt::color(0.9f)); // illum 3: reflection on, km = Ks
    const rt::mesh& m = loaded.geometry;
    REQUIRE(m.face_materials.size() == 3);
    CHECK(m.face_materials[0] == -1); // before any usemtl: the mesh's own material
    CHECK(m.face_materials[1] == 0);
    CHECK(m.face_materials[2] == 1);
    CHECK(rt::triangle_material(m, 0) == m.material);
    CHECK(rt::triangle_material(m, 2) == 1);
}

TEST_CASE("the Cornell box: negative indices, quads and its MTL file")
{
    const std::filesystem::path cornell = std::filesystem::path(RT_SHARED_DIR) / "meshes" / "CornellBox-Original.obj";
    if (!std::filesystem::exists(cornell)) {
        MESSAGE("skipped: " << cornell.string() << " is not there");
        return;
    }
    const rt::obj_result loaded = rt::load_obj(cornell);
    const rt::mesh& m = loaded.geometry;
    CHECK(m.positions.size() == 72);
    CHECK(m.triangles.size() == 36); // 18 quads
    CHECK(m.dropped_degenerate == 0);
    REQUIRE(loaded.materials.size() == 8);
    // the floor is the first quad, "f -4 -3 -2 -1" after its four vertices:
    // its triangles use vertices 0 to 3 only, and the floor material
    CHECK(m.triangles[0][0] < 4);
    CHECK(m.triangles[1][2] < 4);
    REQUIRE(m.face_materials.size() == 36);
    CHECK(loaded.materials[std::size_t(m.face_materials[0])].name == "floor");
    for (const rt::material& mat : loaded.materials)
        if (mat.name == "leftWall")
            CHECK(mat.kd == rt::color(0.63f, 0.065f, 0.05f));
}

TEST_CASE("malformed or missing OBJ and MTL files are one-line errors with file:line:col")
{
    const std::filesystem::path folder = scratch_folder("errors");
    write_file(folder / "good.mtl", "newmtl shiny\nKd 1 1 1\n");
    write_file(folder / "bad.mtl", "newmtl a\nKd 1 x 1\n");
    write_file(folder / "early.mtl", "Kd 1 1 1\n");
    struct bad_case {
        const char* name;
        const char* text;
        const char* location; // the message starts with this, after the folder
        const char* words;
    };
    const bad_case cases[] = {
        {"not a number", "v 0 0 0\nv 1 x 0\n", "e.obj:2:5:", "expected a number for the vertex y, found 'x'"},
        {"NaN", "v 0 nan 0\n", "e.obj:1:5:", "finite"},
        {"too few coordinates", "v 0 0\n", "e.obj:1:6:", "expected a number for the vertex z, found the end of the line"},
        {"index 0", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "e.obj:4:3:", "other than 0"},
        {"index past the last vertex", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n", "e.obj:5:7:",
         "a vertex index from 1 to 3, found 9"},
        {"negative index before the first vertex", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "e.obj:4:9:",
         "a relative vertex index from -1 to -3, found -4"},
        {"normal index without normals", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", "e.obj:4:6:",
         "a normal index from 1 to 0"},
        {"a face of two corners", "v 0 0 0\nv 1 0 0\nf 1 2\n", "e.obj:3:1:", "a face of at least 3 corners, found 2"},
        {"a corner that is not an index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 three\n", "e.obj:4:7:", "'three'"},
        {"malformed MTL line", "mtllib bad.mtl\n", "bad.mtl:2:6:", "expected a number for Kd g, found 'x'"},
        {"MTL statement before newmtl", "mtllib early.mtl\n", "early.mtl:1:1:", "'newmtl name' before 'Kd'"},
        {"binary bytes", "v 0 0 0\n\x01\x02\x03\n", "e.obj:2:1:", "a byte of value 1"},
    };
    for (const bad_case& c : cases) {
        const std::string case_name = c.name;
        CAPTURE(case_name);
        const std::filesystem::path path = write_file(folder / "e.obj", c.text);
        const std::string message = load_error(path);
        CAPTURE(message);
        const std::string where = (folder / c.location).string();
        CHECK(message.rfind(where, 0) == 0);
        CHECK(message.find(c.words) != std::string::npos);
        CHECK(message.find("expected") != std::string::npos);
        CHECK(one_line(message));
    }
    // missing materials: a warning line and the default material, an error with strict (--strict)
    const bad_case strict_cases[] = {
        {"missing material library", "mtllib nowhere.mtl\n", "e.obj:1:8:", "no such file"},
        {"unknown material", "mtllib good.mtl\nusemtl dull\n", "e.obj:2:8:", "known: shiny"},
        {"usemtl without a library", "usemtl shiny\n", "e.obj:1:8:", "found usemtl 'shiny' without one"},
    };
    for (const bad_case& c : strict_cases) {
        const std::string case_name = c.name;
        CAPTURE(case_name);
        const std::filesystem::path path = write_file(folder / "e.obj", c.text);
        std::ostringstream warnings;
        rt::obj_limits limits;
        limits.warnings = &warnings;
        CHECK(load_error(path, limits) == "no error");
        CHECK(warnings.str().rfind((folder / c.location).string() + " warning: ", 0) == 0);
        limits.strict = true;
        const std::string message = load_error(path, limits);
        CAPTURE(message);
        CHECK(message.rfind((folder / c.location).string(), 0) == 0);
        CHECK(message.find(c.words) != std::string::npos);
        CHECK(one_line(message));
    }
    const std::string missing = load_error(folder / "no-such.obj");
    CHECK(missing.find("no such file") != std::string::npos);
    CHECK(missing.rfind((folder / "no-such.obj").string(), 0) == 0);
    CHECK(load_error(folder).find("found a folder") != std::string::npos);
}
