// library_bvh.cpp - the library's accelerator (include/rt/bvh/bvh.hpp,
// include/rt/bvh/accelerator.hpp): the slab test with Ize's factor (Ize, "Robust BVH
// ray traversal", JCGT 2013), BVH build (the same tree for any thread count,
// spatial splits that never cut a triangle's piece) and traversal (the same
// hits as the flat list, on random rays, through closed meshes and on the
// Stanford bunny when /work/shared/meshes holds it). No exercise is called:
// the reference for the BVH is the library's flat list (accelerator_kind::flat).
#include "rt_doctest.hpp"
#include "slab_contract.hpp"
#include "edge_leaks.hpp"
#include "test_scenes.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>
#include <thread>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/bvh/bvh.hpp>
#include <rt/bvh/hit_fill.hpp>
#include <rt/input/obj_loader.hpp>
#include <rt/intersection/offset.hpp>
#include <rt/intersection/spawn.hpp>
#include <rt/intersection/watertight.hpp>

namespace {

using namespace rt_test; // test_scenes.hpp, edge_leaks.hpp

using rt::real;
using rt::vec3;

rt::aabb bounds_of(const rt::mesh& m)
{
    rt::aabb box;
    for (const vec3& p : m.positions)
        box.grow(p);
    return box;
}

} // namespace

TEST_CASE("the slab test handles axis-parallel rays, rays in a slab plane, -0 and flat boxes without NaN")
{
    // the same cases as slab.hpp's hit_box_robust (slab_contract.hpp), through the BVH's precomputed box ray
    rt_test::check_robust_slab([](const rt::aabb& box, const rt::ray& r, real tmin, real tmax, real& tnear) {
        return rt::hit_box(box, rt::make_box_ray(r), tmin, tmax, tnear);
    });
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

namespace {

/// Whether two trees of one width are the same: nodes, boxes, leaves and the primitives of their blocks.
template <class Tree>
bool same_nodes(const Tree& ta, const Tree& tb)
{
    const auto& na = ta.nodes();
    const auto& nb = tb.nodes();
    const auto& pa = ta.blocks();
    const auto& pb = tb.blocks();
    if (na.size() != nb.size() || pa.size() != pb.size())
        return false;
    constexpr int width = int(sizeof(na[0].child) / sizeof(na[0].child[0]));
    bool same = true;
    for (std::size_t i = 0; i < na.size(); ++i)
        for (int c = 0; c < width; ++c) {
            same = same && na[i].child[c] == nb[i].child[c] && na[i].count[c] == nb[i].count[c];
            for (int row = 0; row < 6; ++row)
                same = same && na[i].bounds[row][c] == nb[i].bounds[row][c];
        }
    for (std::size_t i = 0; i < pa.size(); ++i)
        for (int lane = 0; lane < 4; ++lane)
            same = same && pa[i].id[lane] == pb[i].id[lane];
    return same;
}

/// Whether two accelerators hold the same tree (of the width each walks: one path for both, here).
bool same_tree(const rt::accelerator& a, const rt::accelerator& b)
{
    if (a.path() != b.path() || a.stats().depth != b.stats().depth || a.stats().references != b.stats().references)
        return false;
    return a.with_tree([&](const auto& ta) {
        return b.with_tree([&](const auto& tb) {
            if constexpr (std::is_same_v<decltype(ta), decltype(tb)>)
                return same_nodes(ta, tb);
            else
                return false;
        });
    });
}

} // namespace

TEST_CASE("the BVH is the same whatever the number of threads that build it")
{
    std::mt19937 random(5);
    const rt::scene s = random_scene(random, 2000, 6000, true); // large enough to be split among threads
    for (const bool spatial : {false, true}) {
        CAPTURE(spatial);
        rt::bvh_options one, two, four;
        one.threads = 1;
        two.threads = 2;
        four.threads = 4;
        for (rt::bvh_options* o : {&one, &two, &four}) {
            if (spatial) { // forced everywhere, so that the threads share the top of the tree
                o->spatial_budget = 1;
                o->spatial_overlap = 0;
            } else {
                o->spatial_budget = 0;
            }
        }
        const rt::accelerator a(s, rt::accelerator_kind::bvh, one);
        CHECK((a.stats().spatial_splits > 0) == spatial);
        CHECK(same_tree(a, rt::accelerator(s, rt::accelerator_kind::bvh, two)));
        CHECK(same_tree(a, rt::accelerator(s, rt::accelerator_kind::bvh, four)));
        // a request far beyond the machine: at most four threads a core are
        // started (a million were tried to be started before), the same tree
        rt::bvh_options many = four;
        many.threads = 1000000;
        INFO("expected a build asked for a million threads to use a few and make the one-thread tree");
        CHECK(same_tree(a, rt::accelerator(s, rt::accelerator_kind::bvh, many)));
    }
    // 70,000 triangles: the top node is binned on two threads (each half into
    // bins of its own, merged) and the subtrees fork wherever a thread is idle.
    // Without spatial splits (the loop above has them, shared among threads):
    // on these overlapping triangles their search made this case about ten
    // times slower in a Debug build (6 s a build), and the kit check runs
    // this suite once per stage.
    const rt::scene large = random_scene(random, 0, 70000, false);
    rt::bvh_options one, two;
    one.threads = 1;
    two.threads = 2;
    one.spatial_budget = two.spatial_budget = 0;
    const rt::accelerator a(large, rt::accelerator_kind::bvh, one);
    INFO("expected the tree of a one-thread build (nodes, boxes, leaves, the blocks' primitives) from two threads, twice");
    CHECK(same_tree(a, rt::accelerator(large, rt::accelerator_kind::bvh, two)));
    CHECK(same_tree(a, rt::accelerator(large, rt::accelerator_kind::bvh, two)));
}

namespace {

/// Sums [begin, end) by halves as the builder forks a node: the right half
/// offered to the other threads, the left half here; records each thread seen.
long long fork_sum(rt::detail::build_tasks& tasks, long long begin, long long end, std::set<std::thread::id>& seen,
                   std::mutex& seen_mutex)
{
    {
        const std::lock_guard<std::mutex> lock(seen_mutex);
        seen.insert(std::this_thread::get_id());
    }
    if (end - begin <= 64) {
        long long sum = 0;
        for (long long i = begin; i < end; ++i)
            sum += i;
        return sum;
    }
    const long long middle = begin + (end - begin) / 2;
    long long left = 0, right = 0;
    auto right_half = [&] { right = fork_sum(tasks, middle, end, seen, seen_mutex); };
    tasks.fork(right_half, [&] { left = fork_sum(tasks, begin, middle, seen, seen_mutex); });
    return left + right;
}

} // namespace

TEST_CASE("the build's tasks: each runs once whichever thread takes it, and an error reaches the thread that forked")
{
    for (const int threads : {1, 2, 4}) {
        CAPTURE(threads);
        rt::detail::build_tasks tasks;
        std::set<std::thread::id> seen;
        std::mutex seen_mutex;
        long long sum = 0;
        tasks.run(threads, [&] { sum = fork_sum(tasks, 0, 1 << 16, seen, seen_mutex); });
        INFO("expected the sum of 0 .. 65535 from halves forked down to 64 numbers");
        CHECK(sum == 65536LL * 65535 / 2);
        CHECK(seen.size() <= std::size_t(threads));
    }
    for (const bool right_throws : {false, true}) {
        CAPTURE(right_throws);
        rt::detail::build_tasks tasks;
        bool other_ran = false;
        const auto fail = [] { throw std::runtime_error("a task failed"); };
        auto right = [&] {
            if (right_throws)
                fail();
            other_ran = true;
        };
        INFO("expected the exception of either side from run(), after both sides ended");
        CHECK_THROWS_WITH(tasks.run(2, [&] {
            tasks.fork(right, [&] {
                if (!right_throws)
                    fail();
                other_ran = true;
            });
        }),
                          "a task failed");
        if (right_throws)
            CHECK(other_ran); // the left side ran to its end before the right side's error was rethrown
    }
}

TEST_CASE("the build's large arrays: from 8 MB on pages of their own, 2 MB aligned on Linux, every element usable")
{
    using array = rt::detail::large_array<std::uint64_t>;
    using allocator = array::allocator_type;
    for (const std::size_t bytes : {std::size_t(4096), allocator::huge_page_threshold - 8,
                                    allocator::huge_page_threshold, allocator::huge_page_threshold + 12345 * 8}) {
        CAPTURE(bytes);
        array a(bytes / 8);
        const auto address = reinterpret_cast<std::uintptr_t>(a.data());
        INFO("expected the array aligned to a cache line at least, found it at " << address);
        CHECK(address % 64 == 0);
#if defined(__linux__)
        if (bytes >= allocator::huge_page_threshold) {
            INFO("expected an array of 8 MB or more at a 2 MB boundary (a huge page's), found it at " << address);
            CHECK(address % allocator::huge_page == 0);
        }
#endif
        for (std::size_t i = 0; i < a.size(); ++i)
            a[i] = i * 2654435761u;
        a.push_back(7); // grows into a new array and moves every element
        bool same = a.back() == 7;
        for (std::size_t i = 0; i + 1 < a.size() && same; ++i)
            same = a[i] == i * 2654435761u;
        INFO("expected every element written to be read back after the array grew");
        CHECK(same);
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
            c = vec3{real(scale * coordinate(random)), real(scale * coordinate(random)), real(scale * coordinate(random))};
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

TEST_CASE("the spatial search's slices hold the part of a triangle in them, and no more")
{
    // A random triangle across 8 slices of its box: each slice's box is the
    // box of the triangle's part between the slice's planes (its corners
    // there and where its edges cross the planes, computed here in double),
    // up to float rounding. Not the triangle's box cut to the slice, which is
    // larger for a slanted triangle: the search would then see no gain in
    // cutting it. Every fourth triangle has an edge parallel to the planes.
    std::mt19937 random(29);
    std::uniform_real_distribution<double> coordinate(-1000, 1000);
    std::size_t slices = 0, wrong = 0;
    for (int k = 0; k < 1000; ++k) {
        vec3 corner[3];
        for (vec3& c : corner)
            c = vec3{real(coordinate(random)), real(coordinate(random)), real(coordinate(random))};
        const int axis = k % 3;
        if (k % 4 == 0)
            corner[1][axis] = corner[0][axis];
        const rt::packed_primitive p = rt::pack_triangle(corner[0], corner[1], corner[2], 0);
        const rt::aabb box = rt::packed_bounds(p);
        const rt::detail::build_item ref{box, box.center(), 0};
        rt::detail::spatial_bins bins(8);
        const bool wide[3] = {axis == 0, axis == 1, axis == 2};
        bins.reset(box, wide);
        bins.add(&ref, 1, &p);
        const double tolerance = 1e-3; // a few float roundings of coordinates up to 1000 (an ulp: 6e-5)
        for (std::size_t b = 0; b < 8; ++b) {
            const double s0 = double(bins.plane(axis, b)), s1 = double(bins.plane(axis, b + 1));
            double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
            const auto grow = [&](const double q[3]) {
                for (int i = 0; i < 3; ++i) {
                    lo[i] = std::min(lo[i], q[i]);
                    hi[i] = std::max(hi[i], q[i]);
                }
            };
            for (int c = 0; c < 3; ++c) {
                const vec3& u = corner[c];
                const vec3& v = corner[(c + 1) % 3];
                const double q[3] = {double(u.x), double(u.y), double(u.z)};
                if (s0 <= q[axis] && q[axis] <= s1)
                    grow(q);
                for (const double s : {s0, s1}) {
                    const double a = double(u[axis]), e = double(v[axis]);
                    if ((a < s && s < e) || (e < s && s < a)) {
                        const double t = (s - a) / (e - a);
                        double x[3];
                        for (int i = 0; i < 3; ++i)
                            x[i] = double(u[i]) + t * (double(v[i]) - double(u[i]));
                        grow(x);
                    }
                }
            }
            if (lo[0] > hi[0]) // the triangle does not reach this slice
                continue;
            ++slices;
            const rt::aabb& got = bins.slice(axis, b);
            bool same = !got.empty();
            for (int i = 0; i < 3 && same; ++i)
                same = std::abs(double(got.lo[i]) - lo[i]) <= tolerance && std::abs(double(got.hi[i]) - hi[i]) <= tolerance;
            if (!same && wrong++ < 3)
                MESSAGE("slice " << b << " on axis " << axis << ": expected the box of the triangle's part there, "
                                 << "(" << lo[0] << " " << lo[1] << " " << lo[2] << ") .. (" << hi[0] << " " << hi[1]
                                 << " " << hi[2] << "), found " << got);
        }
    }
    MESSAGE(slices << " slices of 1000 triangles, " << wrong << " not the box of the triangle's part");
    CHECK(slices > 4000);
    CHECK(wrong == 0);
}

TEST_CASE("cutting references at a plane: each piece on its side, the pieces within the room, the rest whole")
{
    // 200 random triangles and a plane through their middle; cut with room
    // for all the pieces, for 10 and for none. Afterwards every reference is
    // below the plane (box.hi <= plane) or reaches above it; a cut one has a
    // piece on each side whose boxes hold the triangle's corners on that side;
    // one past the room keeps its whole box; and no room is overrun.
    std::mt19937 random(41);
    std::uniform_real_distribution<double> coordinate(-100, 100);
    std::vector<rt::packed_primitive> prims;
    for (int k = 0; k < 200; ++k) {
        vec3 c[3];
        for (vec3& v : c)
            v = vec3{real(coordinate(random)), real(coordinate(random)), real(coordinate(random))};
        prims.push_back(rt::pack_triangle(c[0], c[1], c[2], std::uint32_t(k)));
    }
    const int axis = 1;
    const real plane = real(3.5);
    std::size_t straddling = 0;
    for (const rt::packed_primitive& p : prims) {
        const rt::aabb b = rt::packed_bounds(p);
        straddling += b.lo[axis] < plane && plane < b.hi[axis] ? 1 : 0;
    }
    REQUIRE(straddling > 50);
    for (const std::size_t room : {std::size_t(1000), std::size_t(10), std::size_t(0)}) {
        CAPTURE(room);
        std::vector<rt::detail::build_item> items(prims.size() + room);
        for (std::size_t i = 0; i < prims.size(); ++i) {
            const rt::aabb b = rt::packed_bounds(prims[i]);
            items[i] = rt::detail::build_item{b, b.center(), std::uint32_t(i)};
        }
        const std::size_t added = rt::detail::cut_references(items.data(), prims.size(), room, axis, plane, prims.data());
        INFO("expected a piece for each triangle across the plane, as the room allows; found " << added);
        CHECK(added == std::min(room, straddling));
        std::size_t whole = 0, wrong = 0;
        std::vector<int> below(prims.size(), 0), above(prims.size(), 0);
        for (std::size_t i = 0; i < prims.size() + added; ++i) {
            const rt::detail::build_item& r = items[i];
            const rt::aabb full = rt::packed_bounds(prims[r.index]);
            const bool is_below = r.box.hi[axis] <= plane;
            (is_below ? below : above)[r.index] += 1;
            if (!is_below && r.box.lo[axis] < plane)
                whole += r.box.lo == full.lo && r.box.hi == full.hi ? 1 : 1000; // only a whole one may cross
            for (int c = 0; c < 3; ++c) { // the corners on the piece's side lie in its box
                const real* v = prims[r.index].v + 3 * c;
                if (is_below ? v[axis] > plane : v[axis] < plane)
                    continue;
                for (int k = 0; k < 3; ++k)
                    wrong += v[k] < r.box.lo[k] || v[k] > r.box.hi[k] ? 1 : 0;
            }
        }
        INFO("expected the references past the room to keep their whole box and cross the plane, found " << whole);
        CHECK(whole == straddling - added);
        INFO("expected every corner on a piece's side inside the piece's box, found " << wrong << " outside");
        CHECK(wrong == 0);
        std::size_t both = 0;
        for (std::size_t i = 0; i < prims.size(); ++i)
            both += below[i] == 1 && above[i] == 1 ? 1 : 0;
        INFO("expected each cut triangle on both sides once, found " << both << " for " << added << " pieces");
        CHECK(both == added);
    }
}

TEST_CASE("SAH costs and an overlap threshold that are not finite numbers of the right sign are refused by name")
{
    const rt::scene s = scene_of(icosphere(1, vec3(0), 1));
    const real nan = std::numeric_limits<real>::quiet_NaN();
    struct bad {
        real traversal, intersection, overlap;
    };
    for (const bad& b : {bad{nan, 1, 0}, bad{-1, 1, 0}, bad{1, 0, 0}, bad{1, -2, 0}, bad{1, rt::infinity, 0},
                         bad{1, 1, nan}, bad{1, 1, -1}}) {
        rt::bvh_options options;
        options.traversal_cost = b.traversal;
        options.intersection_cost = b.intersection;
        options.spatial_overlap = b.overlap;
        std::string message;
        try {
            const rt::accelerator tree(s, rt::accelerator_kind::bvh, options);
        } catch (const rt::error& e) {
            message = e.what();
        }
        INFO("costs " << b.traversal << ", " << b.intersection << ", overlap " << b.overlap << ": got '" << message
                      << "'");
        CHECK(message.find("bvh_options: expected traversal_cost >= 0, intersection_cost > 0") != std::string::npos);
    }
    rt::bvh_options free_walk; // a traversal cost of 0 is a choice, not an error
    free_walk.traversal_cost = 0;
    const rt::accelerator tree(s, rt::accelerator_kind::bvh, free_walk);
    rt::hit_record rec;
    CHECK(tree.closest_hit(rt::ray{vec3(0, 0, 3), vec3(0, 0, -1)}, 0, rt::infinity, rec));
}

TEST_CASE("a spatial budget out of range is held in [0, 4] times the primitives: no overflow, no allocation beyond it")
{
    rt::mesh m = icosphere(2, vec3(0), 1);
    const vec3 d = glm::normalize(vec3(1, 1, real(0.5)));
    for (vec3& v : m.positions)
        v += real(39) * glm::dot(v, d) * d; // long slanted triangles, as above
    const rt::scene s = scene_of(m);
    const std::size_t n = m.triangles.size();
    for (const real asked : {real(-1), std::numeric_limits<real>::quiet_NaN(), real(100), rt::infinity}) {
        CAPTURE(asked);
        rt::bvh_options options;
        options.spatial_budget = asked;
        options.spatial_overlap = 0;
        options.spatial_bins = 32;
        const rt::accelerator tree(s, rt::accelerator_kind::bvh, options);
        const std::size_t refs = tree.stats().references;
        if (!(asked > 0)) {
            INFO("expected a negative or NaN budget to turn spatial splits off, found " << refs << " references for "
                                                                                         << n << " triangles");
            CHECK(refs == n);
        } else {
            INFO("expected at most 5 references a triangle (a budget of 4), found " << refs << " for " << n
                                                                                   << " triangles");
            CHECK(refs > n);
            CHECK(refs <= 5 * n);
        }
    }
}

TEST_CASE("a BVH with spatial splits: every ray through a closed mesh's edges and vertices hits, and hits as the list")
{
    // An icosphere stretched 40 times along a diagonal: long thin slanted
    // triangles whose boxes overlap, the case spatial splits are for. Forced
    // on everywhere (no overlap threshold, one extra reference per triangle,
    // slices narrower than the triangles).
    rt::mesh m = icosphere(3, vec3(0), 1);
    const vec3 d = glm::normalize(vec3(1, 1, real(0.5)));
    for (vec3& v : m.positions)
        v += real(39) * glm::dot(v, d) * d;
    const rt::scene s = scene_of(m);
    rt::bvh_options cut;
    cut.spatial_budget = 1;
    cut.spatial_overlap = 0;
    cut.spatial_bins = 32;
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
    const rt::accelerator flat(s, rt::accelerator_kind::flat);
    std::size_t hits = 0, disagreements = 0;
    for (const rt::ray& r : random_rays(random, 3000)) {
        rt::hit_record a, b;
        const bool in_list = flat.closest_hit(r, 0, rt::infinity, a);
        const bool in_tree = tree.closest_hit(r, 0, rt::infinity, b);
        disagreements += in_list == in_tree && (!in_list || same_hit(a, b)) &&
                                 flat.any_hit(r, 0, rt::infinity) == tree.any_hit(r, 0, rt::infinity)
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
        RT_SKIP(bunny.string() + " is not there (../shared/meshes)");
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
        const vec3 target = box.lo + vec3{unit(random), unit(random), unit(random)} * box.extent();
        const vec3 from = box.center() + glm::length(box.extent()) *
                                             glm::normalize(vec3{unit(random) - real(0.5), unit(random) - real(0.5),
                                                                 unit(random) - real(0.5)});
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

TEST_CASE("many copies of one triangle: the BVH still builds and keeps the last copy, as the list does")
{
    // every centroid is the same point, so no plane separates them
    rt::mesh m;
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    for (int k = 0; k < 1000; ++k)
        m.triangles.push_back({0, 1, 2});
    rt::scene s;
    s.shapes.push_back(m);
    const rt::accelerator tree(s, rt::accelerator_kind::bvh);
    CHECK(tree.stats().depth < rt::bvh::max_depth + 2);
    rt::hit_record rec;
    REQUIRE(tree.closest_hit(rt::ray{{0, 0, 3}, {0, 0, -1}}, 0, rt::infinity, rec));
    CHECK(rec.primitive == 999);
}

TEST_CASE("a leaf block's normals are triangle_normal's, and zero for spheres and unused lanes")
{
    // pack_triangle_block computes its four normals at once where AVX is
    // compiled in (detail::block_normals, bvh/layout.hpp; this suite's
    // library.avx2 build), else lane by lane: either way each must be
    // triangle_normal's, bit for bit. Random triangles at scales 1e-8 to 1e8,
    // slivers, corners on one line, and blocks of one to four lanes with
    // spheres among them
    std::mt19937 random(17);
    std::uniform_real_distribution<real> unit(-1, 1);
    const real scales[] = {real(1e-8), real(1e-3), real(1), real(1e3), real(1e8)};
    std::size_t normals = 0, zero = 0, different = 0;
    for (int round = 0; round < 4000; ++round) {
        rt::packed_primitive p[4];
        const std::size_t n = std::size_t(1 + round % 4);
        for (std::size_t lane = 0; lane < n; ++lane) {
            const real scale = scales[(round + int(lane)) % 5];
            const auto point = [&] { return scale * vec3(unit(random), unit(random), unit(random)); };
            const vec3 a = point(), b = point();
            vec3 c = point();
            if (round % 10 == 1)
                c = a + real(1e-4) * (c - a) + (b - a); // a sliver
            if (round % 25 == 2)
                c = b; // no area
            p[lane] = rt::pack_triangle(a, b, c, std::uint32_t(lane));
            if (round % 9 == 3 && lane == 1)
                p[lane] = rt::pack_sphere(rt::sphere{a, scale, 0}, 1);
        }
        const rt::packed_primitive* lanes[4] = {&p[0], &p[1], &p[2], &p[3]};
        const rt::detail::triangle_block block = rt::detail::pack_triangle_block(lanes, n);
        for (std::size_t lane = 0; lane < 4; ++lane) {
            vec3 expected(0);
            if (lane < n && !(p[lane].id & rt::sphere_flag))
                expected = rt::triangle_normal(vec3(p[lane].v[0], p[lane].v[1], p[lane].v[2]),
                                               vec3(p[lane].v[3], p[lane].v[4], p[lane].v[5]),
                                               vec3(p[lane].v[6], p[lane].v[7], p[lane].v[8]));
            ++normals;
            zero += expected == vec3(0) ? 1 : 0;
            const vec3 got = block.n[lane];
            const bool same = std::memcmp(&got, &expected, sizeof got) == 0;
            if (!same && ++different <= 5) // the first five in full
                CHECK_MESSAGE(same, "lane " << lane << " of " << n << ": expected the normal " << expected
                                            << " (triangle_normal; zero for a sphere or an unused lane), found "
                                            << got);
        }
    }
    MESSAGE(normals << " lanes, " << zero << " without a normal");
    CHECK(zero > 4000);
    CHECK(different == 0);
}

TEST_CASE("a BVH hit's record filled from its block is fill_triangle_record's, field for field")
{
    // rt::detail::fill_triangle_record_strided (bvh/hit_fill.hpp) reads the
    // corners from a leaf block (four values apart) and computes in SSE; its
    // record must be the scalar fill_triangle_record's bit for bit: random
    // triangles at scales 1e-3 to 1e3, both faces, two corners the same (no
    // normal), barycentrics of hits and of negative zeros
    std::mt19937 random(11);
    std::uniform_real_distribution<real> unit(-1, 1), weight(0, 1);
    const real scales[] = {real(1e-3), real(1), real(1e3)};
    std::size_t records = 0, back_faces = 0, no_normal = 0, different = 0;
    for (int round = 0; round < 3000; ++round) {
        const real scale = scales[round % 3];
        const auto point = [&] { return scale * vec3(unit(random), unit(random), unit(random)); };
        const vec3 a = point(), b = point();
        const vec3 c = round % 50 == 0 ? b : point(); // every 50th with two corners the same: no normal
        rt::packed_primitive p{{a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z}, 0};
        const rt::packed_primitive* lanes[4] = {&p, &p, &p, &p};
        const rt::detail::triangle_block block = rt::detail::pack_triangle_block(lanes, 4);
        const int lane = round % 4;
        real b1 = weight(random), b2 = weight(random) * (1 - b1);
        if (round % 7 == 0)
            b2 = real(-0.0);
        const rt::triangle_hit h{scale * weight(random), 1 - b1 - b2, b1, b2};
        const rt::ray r{point(), vec3(unit(random), unit(random), unit(random) + real(0.01))};
        rt::hit_record expected, got;
        rt::fill_triangle_record(a, b, c, block.n[lane], r, h, expected);
        rt::detail::fill_triangle_record_strided(&block.v[0][lane], 4, block.n[lane], r, h, got);
        ++records;
        back_faces += expected.front_face ? 0 : 1;
        no_normal += block.n[lane] == vec3(0) ? 1 : 0;
        if (!same_hit(expected, got) && ++different <= 5) { // the first five in full
            INFO("triangle " << a << " " << b << " " << c << ", barycentrics " << h.b0 << " " << h.b1 << " " << h.b2);
            CHECK_MESSAGE(same_hit(expected, got), "expected point " << expected.point << " +- "
                                                                     << expected.point_error << ", normal "
                                                                     << expected.geometric_normal << "; found "
                                                                     << got.point << " +- " << got.point_error
                                                                     << ", normal " << got.geometric_normal);
        }
    }
    MESSAGE(records << " records, " << back_faces << " back faces, " << no_normal << " without a normal");
    CHECK(back_faces > 1000);
    CHECK(no_normal >= 50);
    CHECK(different == 0);
}

TEST_CASE("a block's closest lane is the one replaces() keeps: the smallest t, at an equal t the largest id")
{
    // rt::detail::closest_lane picks one lane of a block's hits at once; it
    // must be the lane a lane-by-lane search by rt::replaces() keeps, for
    // every mask of hits, with ties at the smallest t, with lanes outside the
    // mask holding smaller t (not hits, never chosen) and with t = infinity
    std::mt19937 random(5);
    const real ts[] = {real(0.5), real(2), real(2), real(7), rt::infinity};
    std::uniform_int_distribution<int> pick_t(0, 4), pick_id(0, 6);
    std::size_t cases = 0, ties = 0, wrong = 0;
    for (int round = 0; round < 400; ++round)
        for (int mask = 1; mask < 16; ++mask) {
            rt::detail::triangle_block b{};
            rt::detail::block_hits hits{};
            for (int lane = 0; lane < 4; ++lane) {
                b.id[lane] = std::uint32_t(pick_id(random));
                hits.t[lane] = ts[pick_t(random)];
                if (!(mask & (1 << lane)) && round % 2 == 0)
                    hits.t[lane] = real(-1); // below every hit: a lane outside the mask must not win
            }
            rt::primitive_hit best{};
            bool found = false;
            int expected = -1, at_best = 0;
            for (int lane = 0; lane < 4; ++lane)
                if ((mask & (1 << lane)) && (!found || rt::replaces(hits.t[lane], b.id[lane], best))) {
                    best.t = hits.t[lane];
                    best.id = b.id[lane];
                    found = true;
                    expected = lane;
                }
            for (int lane = 0; lane < 4; ++lane)
                at_best += (mask & (1 << lane)) && hits.t[lane] == best.t ? 1 : 0;
            ties += at_best > 1 ? 1 : 0;
            const int got = rt::detail::closest_lane(mask, hits, b);
            // lanes with the same t and id are the same hit: either is right
            const bool same = got == expected ||
                              ((mask & (1 << got)) && hits.t[got] == best.t && b.id[got] == best.id);
            if (!same) {
                ++wrong;
                INFO("mask " << mask << ", t " << hits.t[0] << " " << hits.t[1] << " " << hits.t[2] << " "
                             << hits.t[3] << ", ids " << b.id[0] << " " << b.id[1] << " " << b.id[2] << " " << b.id[3]);
                CHECK_MESSAGE(same, "expected lane " << expected << " (the smallest t, then the largest id), found "
                                                     << got);
            }
            ++cases;
        }
    MESSAGE(cases << " blocks, " << ties << " with a tie at the smallest t");
    CHECK(ties > 1000);
    CHECK(wrong == 0);
}

TEST_CASE("flat and BVH accelerators, scalar and SIMD traversal agree hit for hit on random scenes")
{
    std::mt19937 random(2024);
    const int setups[][3] = {{300, 0, 0}, {0, 600, 1}, {150, 300, 1}};
    for (const auto& kind : setups) {
        const rt::scene s = random_scene(random, kind[0], kind[1], kind[2] != 0);
        const rt::accelerator flat(s, rt::accelerator_kind::flat);
        const rt::accelerator tree(s, rt::accelerator_kind::bvh);
        REQUIRE(flat.kind() == rt::accelerator_kind::flat);
        REQUIRE(tree.kind() == rt::accelerator_kind::bvh);
        REQUIRE(tree.stats().nodes > 1);
        std::size_t disagreements = 0;
        for (const rt::ray& r : random_rays(random, 1500)) {
            rt::hit_record from_flat, from_tree;
            const bool flat_hit = flat.closest_hit(r, 0, rt::infinity, from_flat);
            const bool tree_hit = tree.closest_hit(r, 0, rt::infinity, from_tree);
            rt::primitive_hit scalar_hit, simd_hit;
            bool tree_scalar = false, tree_simd = false, any_agree = false;
            tree.with_tree([&](const auto& t) { // the tree of the path the accelerator walks
                tree_scalar = t.closest_hit_scalar(r, 0, rt::infinity, scalar_hit);
                tree_simd = t.closest_hit(r, 0, rt::infinity, simd_hit);
                any_agree = t.any_hit_scalar(r, 0, rt::infinity) == t.any_hit(r, 0, rt::infinity);
            });
            bool agree = flat_hit == tree_hit && tree_scalar == tree_simd && tree_hit == tree_simd && any_agree &&
                         flat.any_hit(r, 0, rt::infinity) == tree.any_hit(r, 0, rt::infinity);
            if (agree && flat_hit)
                agree = same_hit(from_flat, from_tree) && scalar_hit.t == simd_hit.t && scalar_hit.id == simd_hit.id;
            disagreements += agree ? 0 : 1;
        }
        INFO(s.shapes.size() << " shapes (" << kind[0] << " spheres, " << kind[1] << " triangles)");
        CHECK(disagreements == 0);
    }
}

TEST_CASE("the accelerators keep the later shape at an equal t, as the list does")
{
    rt::scene s;
    s.shapes.emplace_back(rt::triangle{{-1, -1, -2}, {1, -1, -2}, {0, 1, -2}, 3});
    s.shapes.emplace_back(rt::triangle{{-1, -1, -2}, {1, -1, -2}, {0, 1, -2}, 4});
    const rt::ray down_z{{0, 0, 0}, {0, 0, -1}};
    for (rt::accelerator_kind kind : {rt::accelerator_kind::flat, rt::accelerator_kind::bvh}) {
        const rt::accelerator world(s, kind);
        rt::hit_record rec;
        REQUIRE(world.closest_hit(down_z, 0, rt::infinity, rec));
        CHECK(rec.shape == 1);
        CHECK(world.any_hit(down_z, 0, 3));
        CHECK_FALSE(world.any_hit(down_z, 0, real(1.5)));
    }
}

TEST_CASE("an accelerator maps every primitive id back to its shape and primitive, empty meshes included")
{
    // ids are given in scene order: a sphere, an empty mesh, a mesh of three
    // triangles, another empty mesh, a triangle, a mesh of two
    rt::scene s;
    s.shapes.emplace_back(rt::sphere{});
    s.shapes.emplace_back(rt::mesh{});
    rt::mesh three;
    three.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    three.triangles = {{0, 1, 2}, {1, 3, 2}, {0, 1, 3}};
    s.shapes.emplace_back(three);
    s.shapes.emplace_back(rt::mesh{});
    s.shapes.emplace_back(rt::triangle{{-1, -1, -2}, {1, -1, -2}, {0, 1, -2}, 0});
    rt::mesh two = three;
    two.triangles.pop_back();
    s.shapes.emplace_back(two);
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> expected = {{0, 0}, {2, 0}, {2, 1}, {2, 2},
                                                                           {4, 0}, {5, 0}, {5, 1}};
    for (rt::accelerator_kind kind : {rt::accelerator_kind::flat, rt::accelerator_kind::bvh}) {
        const rt::accelerator world(s, kind);
        REQUIRE(world.primitive_count() == expected.size());
        for (std::uint32_t id = 0; id < expected.size(); ++id) {
            const rt::primitive_ref ref = world.reference(id);
            INFO("id " << id << ": expected shape " << expected[id].first << ", primitive " << expected[id].second
                       << "; found shape " << ref.shape << ", primitive " << ref.primitive);
            CHECK(ref.shape == expected[id].first);
            CHECK(ref.primitive == expected[id].second);
        }
    }
}
