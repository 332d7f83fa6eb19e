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
#include "test_scenes.hpp"

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

#include <rt/bvh/accelerator.hpp>
#include <rt/intersection/hit_list.hpp>
#include <rt/input/obj_loader.hpp>
#include <rt/intersection/offset.hpp>
#include <rt/intersection/spawn.hpp>
#include <rt/intersection/triangle.hpp>
#include <rt/intersection/watertight.hpp>

namespace {

using namespace rt_test; // test_scenes.hpp

using rt::real;
using rt::vec3;

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
        REQUIRE_MESSAGE(m.hit(tri, rt::ray{{0.25f, 0.5f, 2}, {0, 0, -1}}, 0, 10, rec),
                        "expected a hit at (0.25, 0.5, 0), t = 2, from above; found no hit");
        CHECK_MESSAGE(near(rec.t, 2), "expected t = 2 (the origin is 2 above the plane, |d| = 1), found " << rec.t);
        CHECK_MESSAGE(near(rec.b1, real(0.25)), "expected b1 = u = 0.25 (the weight of corner b), found " << rec.b1);
        CHECK_MESSAGE(near(rec.b2, real(0.5)), "expected b2 = v = 0.5 (the weight of corner c), found " << rec.b2);
        CHECK_MESSAGE(near(rec.point, vec3(0.25f, 0.5f, 0)), "expected the point (0.25, 0.5, 0), found " << rec.point);
        CHECK_MESSAGE(rec.front_face, "expected front_face: the corners turn counter-clockwise seen from the ray");
        CHECK_MESSAGE(near(rec.geometric_normal, vec3(0, 0, 1)),
                      "expected the geometric normal (0, 0, 1), found " << rec.geometric_normal);
        CHECK_MESSAGE(near(rec.normal, vec3(0, 0, 1)), "expected the normal (0, 0, 1), found " << rec.normal);
        CHECK_MESSAGE(rec.material == 4, "expected the triangle's material in the record (fill_triangle_record "
                                         "leaves rec.material to the caller: set it to tri.material), found "
                                             << rec.material);

        // from below: two-sided, the back face, normals turned towards the ray;
        // a direction of length 2 halves t
        REQUIRE_MESSAGE(m.hit(tri, rt::ray{{0.25f, 0.5f, -3}, {0, 0, 2}}, 0, 10, rec),
                        "expected a hit on the back face (a ray from below, det < 0): the test is two-sided, "
                        "only det == 0 misses; found no hit");
        CHECK_MESSAGE(near(rec.t, real(1.5)),
                      "expected t = 1.5 (3 below the plane, |d| = 2: t counts lengths of d), found " << rec.t);
        CHECK_MESSAGE(!rec.front_face, "expected the back face (front_face false) for a ray from below");
        CHECK_MESSAGE(near(rec.geometric_normal, vec3(0, 0, -1)),
                      "expected the normal turned towards the ray, (0, 0, -1), found " << rec.geometric_normal);

        // misses: beyond each edge, parallel in the plane, behind the origin
        CHECK_MESSAGE(!m.hit(tri, rt::ray{{0.6f, 0.6f, 1}, {0, 0, -1}}, 0, 10, rec),
                      "expected a miss beyond the edge b-c (u + v = 1.2 > 1), found a hit");
        CHECK_MESSAGE(!m.hit(tri, rt::ray{{-0.1f, 0.5f, 1}, {0, 0, -1}}, 0, 10, rec),
                      "expected a miss beyond the edge a-c (u = -0.1 < 0), found a hit");
        CHECK_MESSAGE(!m.hit(tri, rt::ray{{0.5f, -0.1f, 1}, {0, 0, -1}}, 0, 10, rec),
                      "expected a miss beyond the edge a-b (v = -0.1 < 0), found a hit");
        CHECK_MESSAGE(!m.hit(tri, rt::ray{{-1, 0.25f, 0}, {1, 0, 0}}, 0, 10, rec),
                      "expected a miss for a ray in the triangle's plane (det = 0), found a hit");
        CHECK_MESSAGE(!m.hit(tri, rt::ray{{0.25f, 0.25f, -1}, {0, 0, -1}}, 0, 10, rec),
                      "expected a miss behind the origin (t = -1 < tmin = 0), found a hit");

        // the edges and corners belong to the triangle (u >= 0, v >= 0, u + v <= 1):
        // a ray down the z axis through (x, y, 0) has det = 1 and u = x, v = y,
        // t = 2 with no rounding, so these hits are exact, not a matter of luck
        struct on_boundary {
            float x, y;
            const char* where;
        };
        const on_boundary boundary[] = {{0, 0.5f, "on the edge a-c, where u = 0"},
                                        {0.5f, 0, "on the edge a-b, where v = 0"},
                                        {0.5f, 0.5f, "on the edge b-c, where u + v = 1"},
                                        {0, 0, "on the corner a, where u = v = 0"},
                                        {1, 0, "on the corner b, where u = 1, v = 0"},
                                        {0, 1, "on the corner c, where u = 0, v = 1"}};
        for (const on_boundary& p : boundary) {
            const bool edge_hit = m.hit(tri, rt::ray{{p.x, p.y, 2}, {0, 0, -1}}, 0, 10, rec);
            CHECK_MESSAGE(edge_hit, "expected a hit at (" << p.x << ", " << p.y << ", 0), " << std::string(p.where)
                                                          << ": the edges are closed (u >= 0, v >= 0, u + v <= 1 "
                                                             "hit; only u < 0, v < 0, u + v > 1 miss); found a miss");
            if (edge_hit)
                CHECK_MESSAGE(near(rec.t, 2), "expected t = 2 at (" << p.x << ", " << p.y << ", 0), found " << rec.t);
        }

        // the interval [tmin, tmax] is closed
        CHECK_MESSAGE(!m.hit(tri, rt::ray{{0.25f, 0.25f, 2}, {0, 0, -1}}, 0, real(1.5), rec),
                      "expected a miss: t = 2 is beyond tmax = 1.5; found a hit");
        CHECK_MESSAGE(!m.hit(tri, rt::ray{{0.25f, 0.25f, 2}, {0, 0, -1}}, real(2.5), 10, rec),
                      "expected a miss: t = 2 is before tmin = 2.5; found a hit");
        CHECK_MESSAGE(m.hit(tri, rt::ray{{0.25f, 0.25f, 2}, {0, 0, -1}}, 0, 2, rec),
                      "expected a hit at t = 2 = tmax: the interval [tmin, tmax] is closed; found a miss");

        // a tilted triangle: a = (1,0,0), b = (0,2,0), c = (0,0,3) spans the plane
        // x + y/2 + z/3 = 1; the ray from 0 along (1,1,1) meets it at t = 6/11,
        // where x = b0, y = 2 b1, z = 3 b2: b0 = 6/11, b1 = 3/11, b2 = 2/11.
        const rt::triangle tilted{{1, 0, 0}, {0, 2, 0}, {0, 0, 3}, -1};
        REQUIRE_MESSAGE(m.hit(tilted, rt::ray{{0, 0, 0}, {1, 1, 1}}, 0, 10, rec),
                        "expected the ray from the origin along (1, 1, 1) to hit the tilted triangle at t = 6/11; "
                        "found no hit");
        CHECK_MESSAGE(near(rec.t, real(6) / 11), "expected t = 6/11 = 0.5454..., found " << rec.t);
        CHECK_MESSAGE(near(rec.b1, real(3) / 11), "expected b1 = 3/11 = 0.2727..., found " << rec.b1);
        CHECK_MESSAGE(near(rec.b2, real(2) / 11), "expected b2 = 2/11 = 0.1818..., found " << rec.b2);
        CHECK_MESSAGE(near(rec.point, vec3(real(6) / 11)), "expected the point (6/11, 6/11, 6/11), found " << rec.point);
        // (b - a) x (c - a) = (6, 3, 2) points away from the origin: the ray
        // from the origin meets the back
        CHECK_MESSAGE(!rec.front_face, "expected the back face: (b - a) x (c - a) = (6, 3, 2) points away from the ray");
        CHECK_MESSAGE(near(rec.geometric_normal, -vec3(6, 3, 2) / real(7)),
                      "expected the normal -(6, 3, 2) / 7, turned towards the ray, found " << rec.geometric_normal);
    }
}

// =============================================================================
// The BVH against the list
// =============================================================================

TEST_CASE("the list returns the closest hit and the any-hit answer of the library's BVH on random scenes")
{
    // The library's BVH (rt::accelerator, tested in library_bvh) is the oracle:
    // the same hits, the same shape at an equal t, the same any-hit answers.
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
        const rt::accelerator tree(s, rt::accelerator_kind::bvh);
        std::size_t hits = 0;
        const std::vector<rt::ray> rays = random_rays(random, 1500);
        for (std::size_t k = 0; k < rays.size(); ++k) {
            const rt::ray& r = rays[k];
            rt::hit_record from_list, from_tree;
            const bool list_hit = rt::closest_hit_list(s, r, 0, rt::infinity, from_list);
            const bool tree_hit = tree.closest_hit(r, 0, rt::infinity, from_tree);
            INFO("ray " << k << " of " << rays.size() << ": " << r);
            // std::string: doctest prints a char* (what a ?: of two literals is) as a pointer
            REQUIRE_MESSAGE(list_hit == tree_hit, "expected " << std::string(tree_hit ? "a hit" : "no hit")
                                                              << ", found " << std::string(list_hit ? "a hit" : "none"));
            if (list_hit) {
                ++hits;
                REQUIRE_MESSAGE(same_hit(from_list, from_tree),
                                "expected shape " << from_tree.shape << " at t = " << from_tree.t << ", found shape "
                                                  << from_list.shape << " at t = " << from_list.t
                                                  << ": the nearest hit, and at an equal t the later shape");
            }
            // any hit, with tmax a little before and a little beyond the closest
            // hit (not at its computed t: there the answer depends on rounding,
            // see docs/stages/04-triangle.md) and at infinity
            const real before = list_hit ? from_list.t * (1 - real(1) / 1024) : real(1);
            const real beyond = list_hit ? from_list.t * (1 + real(1) / 1024) : real(10);
            for (real tmax : {before, beyond, rt::infinity}) {
                const bool expected = tree.any_hit(r, 0, tmax);
                REQUIRE_MESSAGE(rt::any_hit_list(s, r, 0, tmax) == expected,
                                "any_hit_list with tmax = " << tmax << ": expected " << std::string(expected ? "true" : "false"));
            }
        }
        MESSAGE(kind_name << ": " << s.shapes.size() << " shapes, " << rays.size() << " rays, " << hits << " hits");
        CHECK_MESSAGE(hits > rays.size() / 10, "expected the random scene to be hit by a tenth of the rays at least");
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
    // last, the farthest: a list that keeps the last hit it finds (tmax not
    // narrowed to the closest t so far) answers this sphere
    rt::sphere farthest_ball;
    farthest_ball.center = vec3(0, 0, -20);
    farthest_ball.material = 5;
    s.shapes.emplace_back(farthest_ball);
    const rt::ray down_z{{0, 0, 0}, {0, 0, -1}};
    rt::hit_record rec;
    {
        INFO("the ray from the origin down -z meets shapes 2 and 3 (the same triangle twice, z = -2) at t = 2, "
             "shape 1 (the sphere at z = -5) at t = 4, shape 0 (z = -10) at t = 9 and shape 4 (z = -20) at t = 19: "
             "expected the closest, and at an equal t the later shape, 3 (material 4); shape 4 means the last hit "
             "found was kept: pass the closest t so far as tmax to the next shape");
        REQUIRE_MESSAGE(rt::closest_hit_list(s, down_z, 0, rt::infinity, rec), "expected a hit, found none");
        CHECK(rec.shape == 3);
        CHECK(rec.material == 4);
        CHECK_MESSAGE(near(rec.t, 2), "expected t = 2, found " << rec.t);
    }
    // beyond the triangles: the near sphere, whose surface is at z = -4
    {
        INFO("tmin = 3, beyond the triangles at t = 2: expected the sphere at z = -5 (shape 1, material 2), entered at "
             "t = 4, at (0, 0, -4) with the normal (0, 0, 1), not the farther spheres, shape 0 (t = 9) and shape 4 "
             "(t = 19)");
        REQUIRE_MESSAGE(rt::closest_hit_list(s, down_z, 3, rt::infinity, rec), "expected a hit, found none");
        CHECK(rec.shape == 1);
        CHECK_MESSAGE(near(rec.t, 4), "expected t = 4, found " << rec.t);
        CHECK(rec.material == 2);
        CHECK_MESSAGE(near(rec.point, vec3(0, 0, -4)), "expected the point (0, 0, -4), found " << rec.point);
        CHECK_MESSAGE(near(rec.geometric_normal, vec3(0, 0, 1)),
                      "expected the geometric normal (0, 0, 1), found " << rec.geometric_normal);
    }
    // a tmax before everything: no hit
    CHECK_FALSE_MESSAGE(rt::closest_hit_list(s, down_z, 0, real(1.5), rec),
                        "expected no hit with tmax = 1.5 (the nearest shape is at t = 2), found shape "
                            << rec.shape << " at t = " << rec.t);
    CHECK_FALSE_MESSAGE(rt::any_hit_list(s, down_z, 0, real(1.5)),
                        "expected any_hit_list false with tmax = 1.5 (the nearest shape is at t = 2), found true");
}

TEST_CASE("many copies of one triangle: the list keeps the last copy")
{
    // 1000 shapes of the scene, all the same triangle, every other one a single
    // triangle and every other a mesh of that one triangle: the ray down the z
    // axis meets each at t = 3 exactly (an axis-parallel ray onto the plane
    // z = 0: nothing to round), so only the list's own tie rule picks one, and
    // the rule is the later shape.
    // (One mesh of 1000 copies would test the library's mesh code instead: a
    // mesh is one shape, whose closest triangle hit_shape picks.)
    rt::scene s;
    const vec3 a(-1, -1, 0), b(1, -1, 0), c(0, 1, 0);
    for (int k = 0; k < 1000; ++k) {
        if (k % 2 == 0) {
            s.shapes.emplace_back(rt::triangle{a, b, c, k}); // material k names the copy
        } else {
            rt::mesh m;
            m.positions = {a, b, c};
            m.triangles.push_back({0, 1, 2});
            m.material = k;
            s.shapes.emplace_back(std::move(m));
        }
    }
    rt::hit_record rec;
    REQUIRE_MESSAGE(rt::closest_hit_list(s, rt::ray{{0, 0, 3}, {0, 0, -1}}, 0, rt::infinity, rec),
                    "expected the ray down the z axis to hit the 1000 copies of the triangle at t = 3, found no hit");
    CHECK_MESSAGE(rec.shape == 999u, "expected shape 999, the last of the 1000 copies (shapes 0 .. 999, all hit at t = "
                                     "3): at an equal t the later shape wins; pass the closest t so far as tmax and keep "
                                     "a hit at t == tmax; found shape "
                                         << rec.shape << std::string(rec.shape == 0 ? " (the first copy)" : ""));
    CHECK_MESSAGE(rec.material == 999, "expected material 999, shape 999's (each copy has its index as material), "
                                       "found " << rec.material << ": set rec from the shape kept");
    CHECK_MESSAGE(near(rec.t, 3), "expected t = 3, found " << rec.t);
}

namespace {

/// What the list asked of the hit function it was given. A shape_hit_function
/// is a plain function pointer and carries no state, so the one test below
/// records the calls here (one thread; reset before each use).
struct recorded_calls {
    int count = 0;
    std::vector<int> shapes; // the material index of each shape asked about: the shape's index in the scene
};

recorded_calls& calls_to_counting_hit()
{
    static recorded_calls calls;
    return calls;
}

/// A hit function that records each call and answers without geometry: every
/// sphere is "hit" at t = its radius (if that is in [tmin, tmax]), although
/// the test's ray passes far from all of them, so only a list that calls
/// this function (not hit_shape) finds a hit at all.
bool counting_hit(const rt::shape& item, const rt::ray& r, real tmin, real tmax, rt::hit_record& rec)
{
    recorded_calls& calls = calls_to_counting_hit();
    ++calls.count;
    const rt::sphere* ball = std::get_if<rt::sphere>(&item);
    calls.shapes.push_back(ball ? ball->material : -1);
    if (!ball || !(tmin <= ball->radius && ball->radius <= tmax))
        return false;
    rec.t = ball->radius;
    rec.point = r.at(rec.t);
    rec.geometric_normal = rec.normal = -glm::normalize(r.direction);
    rec.front_face = true;
    rec.material = ball->material;
    rec.primitive = 0;
    return true;
}

} // namespace

TEST_CASE("the list tests every shape with the hit function it is given, once each, and keeps that function's closest hit")
{
    // Four spheres well off the ray: hit_shape misses them all; counting_hit
    // "hits" each at t = its radius, so the closest is shape 1 (t = 1).
    rt::scene s;
    const real radii[] = {3, 1, 2, 5};
    for (int k = 0; k < 4; ++k) {
        rt::sphere ball;
        ball.center = vec3(real(100 * (k + 1)), 100, 0);
        ball.radius = radii[k];
        ball.material = k; // names the shape in the recorded calls
        s.shapes.emplace_back(ball);
    }
    const rt::ray down_z{{0, 0, 0}, {0, 0, -1}};
    calls_to_counting_hit() = recorded_calls{};
    rt::hit_record rec;
    const bool hit = rt::closest_hit_list(s, down_z, 0, rt::infinity, rec, counting_hit);
    const recorded_calls calls = calls_to_counting_hit();
    std::string asked;
    for (int shape : calls.shapes)
        asked += (asked.empty() ? "" : ", ") + std::to_string(shape);
    INFO("closest_hit_list must test each shape with its parameter `hit` (the stage-04 program passes the textbook "
         "methods through it), not call hit_shape itself: expected 4 calls, for shapes 0, 1, 2, 3, found "
         << calls.count << " calls, for shapes (" << asked << ")");
    REQUIRE(calls.count == 4);
    CHECK(asked == "0, 1, 2, 3"); // in scene order, each once
    INFO("the hit function reports shapes 0..3 hit at t = 3, 1, 2, 5: expected the closest, shape 1 at t = 1");
    REQUIRE_MESSAGE(hit, "expected closest_hit_list to return true, found false");
    CHECK(rec.shape == 1u);
    CHECK(rec.t == 1);
    CHECK(rec.material == 1);
}
