// Stage 04 - triangles and the closest hit of a list of shapes.
//
// The two exercises: Moller-Trumbore (Moller, Trumbore 1997) finds t and the
// barycentrics worked out by hand, and closest_hit_list returns the nearest
// shape, its index, the later shape at an equal t, and the same hits as the
// library's BVH on random scenes.
//
// The library's own triangle machinery has its suites: the watertight test and
// SIMD leaves (library_watertight.cpp), spawned rays (library_spawn.cpp), the
// slab test and the BVH (library_bvh.cpp), the OBJ loader (library_obj_check.cpp).
//
// Only stage-04 exercises (Moller-Trumbore, closest_hit_list) and unmarked
// library code are called: scenes, meshes and rays are built here.
#include "rt_doctest.hpp"

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

#include <rt/accelerator.hpp>
#include <rt/bvh.hpp>
#include <rt/hit_list.hpp>
#include <rt/obj_loader.hpp>
#include <rt/offset.hpp>
#include <rt/spawn.hpp>
#include <rt/triangle.hpp>
#include <rt/watertight.hpp>

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

/// Targets on a closed mesh's surface that rays from inside are aimed at,
/// each with the triangles it lies on: every vertex (its fan), every edge's
/// midpoint and seven points along it (the edge's two triangles).
struct surface_target {
    vec3 point;
    std::vector<std::size_t> triangles;
};

// --- files written by the OBJ tests ---------------------------------------------

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
