// library_dispatch.cpp - run-time dispatch (include/rt/bvh/dispatch.hpp): a
// program compiled without AVX2 in its target (-O2 alone, on x86-64) holds
// the 4-wide SSE path and the 8-wide AVX2 path (with g++ and clang++ also
// that path compiled for AVX-512), and rt::accelerator walks the widest the
// CPU runs. The suite builds one accelerator per path this program
// holds and this CPU runs (the constructor's bvh_path forces it) and checks
// that they return the same hits, bit for bit, as each other, as the scalar
// walk of their own tree (node and leaf tests one value at a time) and as the
// flat list (the watertight test and the stable sphere method, one primitive
// at a time): t, shape, primitive, material, barycentrics, the point and its
// error bound, both normals, the side, and every any-hit answer. Speed is
// never bought with a different hit. Random scenes of spheres, triangles that
// share edges and closed meshes, and the Stanford bunny when ../shared holds
// it. Built as the other suites are, so in a double or arm64 build, or with an
// AVX2 target, it checks the one path there is. tests/CMakeLists.txt runs its
// first two cases again on an emulated CPU without AVX2, where the automatic
// path must be sse. No exercise is called.
#include "rt_doctest.hpp"
#include "test_scenes.hpp"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/bvh/builtins.hpp>
#include <rt/input/obj_loader.hpp>

namespace {

using rt::real;
using rt::vec3;

/// The paths this program holds and this CPU runs.
std::vector<rt::bvh_path> paths_here()
{
    if (!rt::accelerator::dispatches)
        return {rt::accelerator::automatic_path()};
    std::vector<rt::bvh_path> paths = {rt::bvh_path::sse};
    if (rt::detail::cpu_runs_avx2())
        paths.push_back(rt::bvh_path::avx2);
    if (rt::accelerator::dispatches_avx512 && rt::detail::cpu_runs_avx512())
        paths.push_back(rt::bvh_path::avx512);
    return paths;
}

std::string listed(const std::vector<rt::bvh_path>& paths)
{
    std::string text;
    for (rt::bvh_path p : paths)
        text += (text.empty() ? "" : ", ") + std::string(rt::describe(p));
    return text;
}

/// Equal bits (so +0 is not -0, and a NaN equals only the same NaN).
bool same_bits(real a, real b)
{
    return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_bits(const vec3& a, const vec3& b)
{
    return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

/// Every field of two hit records, bit for bit.
bool identical(const rt::hit_record& a, const rt::hit_record& b)
{
    return same_bits(a.t, b.t) && same_bits(a.point, b.point) && same_bits(a.point_error, b.point_error) &&
           same_bits(a.geometric_normal, b.geometric_normal) && same_bits(a.normal, b.normal) &&
           a.front_face == b.front_face && a.material == b.material && a.shape == b.shape &&
           a.primitive == b.primitive && same_bits(a.b1, b.b1) && same_bits(a.b2, b.b2);
}

/// The nodes' width of the tree an accelerator walks.
int node_width(const rt::accelerator& a)
{
    return a.with_tree([](const auto& tree) {
        using node = typename std::decay_t<decltype(tree.nodes())>::value_type;
        return int(sizeof(node::child) / sizeof(std::uint32_t));
    });
}

/// What one path makes of a set of rays, and how many of them it got wrong.
struct comparison {
    std::size_t rays = 0, hits = 0;
    std::size_t against_flat = 0;   ///< rays whose record or any-hit answer differs from the flat list's
    std::size_t against_scalar = 0; ///< rays whose SIMD walk differs from the scalar walk of the same tree
    std::size_t against_first = 0;  ///< rays whose record differs from the first path's
};

/// Traces `rays` with `tree` (one path), `flat` (the reference) and, for each
/// ray, the scalar walk of the same tree; `first` holds the first path's
/// records (filled when empty), so every later path is also compared with it.
/// Rays are traced over [0, infinity) and, for any hit, over a segment that
/// ends half way to the closest hit and one that ends past it.
comparison compare(const rt::accelerator& tree, const rt::accelerator& flat, const std::vector<rt::ray>& rays,
                   std::vector<rt::hit_record>& first, std::vector<char>& first_hit)
{
    comparison c;
    const bool record_first = first.empty();
    if (record_first) {
        first.resize(rays.size());
        first_hit.resize(rays.size());
    }
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const rt::ray& r = rays[i];
        rt::hit_record want, got;
        const bool hit_flat = flat.closest_hit(r, 0, rt::infinity, want);
        const bool hit_tree = tree.closest_hit(r, 0, rt::infinity, got);
        ++c.rays;
        c.hits += hit_flat ? 1 : 0;
        bool same = hit_flat == hit_tree && (!hit_flat || identical(want, got)) &&
                    flat.any_hit(r, 0, rt::infinity) == tree.any_hit(r, 0, rt::infinity);
        if (hit_flat) {
            const real half = want.t / 2, past = want.t * 2;
            same = same && flat.any_hit(r, 0, half) == tree.any_hit(r, 0, half) &&
                   flat.any_hit(r, half, past) == tree.any_hit(r, half, past);
        }
        c.against_flat += same ? 0 : 1;
        // the same tree walked one value at a time
        const bool scalar_same = tree.with_tree([&](const auto& t) {
            rt::primitive_hit simd_hit, scalar_hit;
            const bool a = t.closest_hit(r, 0, rt::infinity, simd_hit);
            const bool b = t.closest_hit_scalar(r, 0, rt::infinity, scalar_hit);
            bool agree = a == b && t.any_hit(r, 0, rt::infinity) == t.any_hit_scalar(r, 0, rt::infinity);
            if (agree && a)
                agree = same_bits(simd_hit.t, scalar_hit.t) && simd_hit.id == scalar_hit.id &&
                        same_bits(simd_hit.b0, scalar_hit.b0) && same_bits(simd_hit.b1, scalar_hit.b1) &&
                        same_bits(simd_hit.b2, scalar_hit.b2);
            return agree;
        });
        c.against_scalar += scalar_same ? 0 : 1;
        if (record_first) {
            first[i] = got;
            first_hit[i] = hit_tree ? 1 : 0;
        } else {
            const bool agree = (first_hit[i] != 0) == hit_tree && (!hit_tree || identical(first[i], got));
            c.against_first += agree ? 0 : 1;
        }
    }
    return c;
}

/// Rays from around `box` to random points inside it, and from its centre outwards.
std::vector<rt::ray> rays_at(const rt::aabb& box, std::mt19937& random, int count)
{
    std::uniform_real_distribution<real> unit(0, 1);
    std::vector<rt::ray> rays;
    for (int k = 0; k < count; ++k) {
        const real u = unit(random), v = unit(random), w = unit(random);
        const vec3 target = box.lo + vec3{u, v, w} * box.extent();
        const real a = unit(random) - real(0.5), b = unit(random) - real(0.5), c = unit(random) - real(0.5);
        const vec3 away = glm::normalize(vec3{a, b, c});
        if (k % 2 == 0) {
            const vec3 from = box.center() + glm::length(box.extent()) * away;
            rays.push_back(rt::ray{from, target - from});
        } else {
            rays.push_back(rt::ray{box.center(), away});
        }
    }
    return rays;
}

} // namespace

TEST_CASE("an accelerator walks the path this program and this CPU allow, and says which")
{
    const std::vector<rt::bvh_path> held = paths_here();
    const rt::bvh_path best = rt::accelerator::automatic_path();
    const std::string program = rt::accelerator::dispatches ? "dispatches" : "does not dispatch";
    const std::string cpu = rt::detail::cpu_runs_avx512() ? "runs AVX-512 and AVX2"
                            : rt::detail::cpu_runs_avx2()   ? "runs AVX2, not AVX-512"
                                                            : "does not run AVX2";
    MESSAGE("this program " << program << std::string(rt::accelerator::dispatches_avx512 ? " (AVX-512 too)" : "")
                            << "; this CPU " << cpu << "; paths: " << listed(held)
                            << "; automatic: " << std::string(rt::describe(best)));
    CHECK(best == held.back()); // the widest path that runs
    // a run on an emulated CPU says which path it must take (tests/CMakeLists.txt:
    // sse under qemu-x86_64 -cpu Nehalem, whose CPUID has no AVX)
    if (const char* expected = std::getenv("RT_TEST_EXPECT_PATH"))
        CHECK(std::string(rt::name_of(best)) == expected);
    if (rt::accelerator::dispatches)
        CHECK(best == (rt::accelerator::dispatches_avx512 && rt::detail::cpu_runs_avx512() ? rt::bvh_path::avx512
                       : rt::detail::cpu_runs_avx2()                                        ? rt::bvh_path::avx2
                                                                                            : rt::bvh_path::sse));

    CHECK(std::string(rt::describe(rt::bvh_path::avx512)) == "avx512 (8-wide)");
    CHECK(std::string(rt::describe(rt::bvh_path::avx2)) == "avx2 (8-wide)");
    CHECK(std::string(rt::describe(rt::bvh_path::sse)) == "sse (4-wide)");
    CHECK(std::string(rt::describe(rt::bvh_path::scalar)) == "scalar (4-wide)");

    std::mt19937 random(43);
    const rt::scene s = rt_test::random_scene(random, 50, 200, false);
    const rt::accelerator automatic(s);
    CHECK(automatic.path() == best);
    CHECK(std::string(automatic.simd_path()) == rt::describe(best));
    for (rt::bvh_path p : held) {
        const rt::accelerator forced(s, rt::accelerator_kind::bvh, {}, p);
        CAPTURE(rt::describe(p));
        CHECK(forced.path() == p);
        CHECK(node_width(forced) == (p == rt::bvh_path::avx2 || p == rt::bvh_path::avx512 ? 8 : 4));
        CHECK(forced.stats().nodes > 1);
    }
    // a path the program does not hold, or the CPU does not run, is refused by name
    for (rt::bvh_path p : {rt::bvh_path::scalar, rt::bvh_path::sse, rt::bvh_path::avx2, rt::bvh_path::avx512}) {
        bool is_held = false;
        for (rt::bvh_path h : held)
            is_held = is_held || h == p;
        if (!is_held)
            CHECK_THROWS_AS(rt::accelerator(s, rt::accelerator_kind::bvh, {}, p), rt::error);
    }
}

TEST_CASE("every path returns the flat list's hits bit for bit, and its own scalar walk's")
{
    const std::vector<rt::bvh_path> held = paths_here();
    std::mt19937 random(2043);
    const int setups[][3] = {{300, 0, 0}, {0, 600, 1}, {150, 300, 1}};
    for (const auto& kind : setups) {
        const rt::scene s = rt_test::random_scene(random, kind[0], kind[1], kind[2] != 0);
        const std::vector<rt::ray> rays = rt_test::random_rays(random, 3000);
        const rt::accelerator flat(s, rt::accelerator_kind::flat);
        std::vector<rt::hit_record> first;
        std::vector<char> first_hit;
        for (rt::bvh_path p : held) {
            const rt::accelerator tree(s, rt::accelerator_kind::bvh, {}, p);
            const comparison c = compare(tree, flat, rays, first, first_hit);
            INFO(kind[0] << " spheres, " << kind[1] << " triangles" << (kind[2] ? " and two meshes" : "") << ", path "
                         << rt::describe(p) << ": " << c.rays << " rays, " << c.hits << " hits");
            CHECK(c.hits > c.rays / 10);
            CHECK(c.against_flat == 0);
            CHECK(c.against_scalar == 0);
            CHECK(c.against_first == 0);
        }
    }
}

TEST_CASE("every path returns the flat list's hits on the Stanford bunny")
{
    const std::filesystem::path bunny = std::filesystem::path(RT_SHARED_DIR) / "meshes" / "stanford-bunny.obj";
    if (!std::filesystem::exists(bunny)) {
        RT_SKIP(bunny.string() + " is not there (../shared/meshes)");
    }
    const rt::scene s = rt_test::scene_of(rt::load_obj(bunny).geometry);
    rt::aabb box;
    for (const vec3& p : std::get<rt::mesh>(s.shapes[0]).positions)
        box.grow(p);
    std::mt19937 random(4343);
    const std::vector<rt::ray> rays = rays_at(box, random, 150); // the flat list tests 69451 triangles a ray
    const rt::accelerator flat(s, rt::accelerator_kind::flat);
    std::vector<rt::hit_record> first;
    std::vector<char> first_hit;
    for (rt::bvh_path p : paths_here()) {
        const rt::accelerator tree(s, rt::accelerator_kind::bvh, {}, p);
        const comparison c = compare(tree, flat, rays, first, first_hit);
        INFO("bunny, path " << rt::describe(p) << ": " << c.rays << " rays, " << c.hits << " hits");
        CHECK(c.hits > c.rays / 4);
        CHECK(c.against_flat == 0);
        CHECK(c.against_scalar == 0);
        CHECK(c.against_first == 0);
    }
}

TEST_CASE("the paths agree with each other on many rays through the bunny")
{
    // the flat list is too slow for many rays through 69451 triangles: the
    // paths against each other and against their own scalar walk
    const std::filesystem::path bunny = std::filesystem::path(RT_SHARED_DIR) / "meshes" / "stanford-bunny.obj";
    if (!std::filesystem::exists(bunny)) {
        RT_SKIP(bunny.string() + " is not there (../shared/meshes)");
    }
    const rt::scene s = rt_test::scene_of(rt::load_obj(bunny).geometry);
    rt::aabb box;
    for (const vec3& p : std::get<rt::mesh>(s.shapes[0]).positions)
        box.grow(p);
    std::mt19937 random(434343);
    const std::vector<rt::ray> rays = rays_at(box, random, 20000);
    std::vector<std::vector<rt::hit_record>> records;
    std::vector<std::vector<char>> hit;
    std::size_t scalar_differ = 0;
    const std::vector<rt::bvh_path> held = paths_here();
    for (rt::bvh_path p : held) {
        const rt::accelerator tree(s, rt::accelerator_kind::bvh, {}, p);
        records.emplace_back(rays.size());
        hit.emplace_back(rays.size());
        for (std::size_t i = 0; i < rays.size(); ++i) {
            hit.back()[i] = tree.closest_hit(rays[i], 0, rt::infinity, records.back()[i]) ? 1 : 0;
            const bool blocked = tree.any_hit(rays[i], 0, rt::infinity);
            const bool same = tree.with_tree([&](const auto& t) {
                rt::primitive_hit scalar_hit;
                const bool b = t.closest_hit_scalar(rays[i], 0, rt::infinity, scalar_hit);
                return b == (hit.back()[i] != 0) && blocked == b && t.any_hit_scalar(rays[i], 0, rt::infinity) == b &&
                       (!b || (same_bits(scalar_hit.t, records.back()[i].t) &&
                               same_bits(scalar_hit.b1, records.back()[i].b1) &&
                               same_bits(scalar_hit.b2, records.back()[i].b2)));
            });
            scalar_differ += same ? 0 : 1;
        }
    }
    std::size_t hits = 0, differ = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hits += hit[0][i];
        for (std::size_t k = 1; k < records.size(); ++k)
            differ += hit[k][i] == hit[0][i] && (!hit[0][i] || identical(records[k][i], records[0][i])) ? 0 : 1;
    }
    MESSAGE("bunny: " << rays.size() << " rays, " << hits << " hits; paths " << listed(held) << ": " << differ
                      << " records differ between paths, " << scalar_differ << " from the scalar walk");
    CHECK(hits > rays.size() / 4);
    CHECK(differ == 0);
    CHECK(scalar_differ == 0);
}
