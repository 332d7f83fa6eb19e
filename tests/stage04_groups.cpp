// Stage 04 - groups: the ray-box slab test and a hierarchy of boxes over the
// scene's primitives (include/rt/intersection/slab.hpp, include/rt/intersection/groups.hpp).
//
// The three exercises, each by its contract:
//  - hit_box_textbook: hits and misses worked out by hand (axis-parallel
//    rays, -0, an origin inside, the interval [tmin, tmax], the empty box),
//    then random boxes and rays against the exact answer, on rays that clear
//    the box's boundary by a margin. Rays that graze an edge or lie in a face
//    plane are left out: there the book's form may fail, and a more careful
//    answer must pass too (library_slab.cpp shows the failures on the
//    library's copy of the book's form).
//  - build_groups: every item in exactly one leaf, leaves of 1 .. leaf_size
//    items, each node's box encloses its items and its children's boxes, the
//    median split (count / 2 to the left) along the longest axis of the
//    centroids.
//  - closest_hit_groups: the same hit as closest_hit_list on random scenes
//    and rays (ties included), and counted item tests: a ray that misses the
//    root box tests no item; along a row of spheres the nearest is tested
//    first and the others are skipped; on groups built by hand (judged
//    apart from build_groups), the nearer child first, the tie rule, and a
//    box entered a rounding error beyond a tied hit still visited (told
//    apart from the tie rule by whether the later item was tested at all).
//
// Only stage-04 exercises and unmarked library code are called.
#include "rt_doctest.hpp"
#include "test_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <rt/intersection/groups.hpp>
#include <rt/intersection/hit_list.hpp>
#include <rt/scene/scene.hpp>
#include <rt/intersection/slab.hpp>

namespace {

using rt::real;
using rt::vec3;

const real inf = std::numeric_limits<real>::infinity();

rt::aabb box_of(const vec3& lo, const vec3& hi)
{
    rt::aabb b;
    b.lo = lo;
    b.hi = hi;
    return b;
}

bool encloses(const rt::aabb& outer, const rt::aabb& inner)
{
    return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z &&
           inner.hi.x <= outer.hi.x && inner.hi.y <= outer.hi.y && inner.hi.z <= outer.hi.z;
}

/// Where the line p + t d is inside the box, in long double from the same
/// inputs: [enter, exit] (enter > exit: never). Components of d are nonzero.
void exact_interval(const rt::aabb& box, const rt::ray& r, long double& enter, long double& exit)
{
    enter = -std::numeric_limits<long double>::infinity();
    exit = std::numeric_limits<long double>::infinity();
    for (int k = 0; k < 3; ++k) {
        const long double d = r.direction[k], p = r.origin[k];
        long double t0 = ((long double)box.lo[k] - p) / d, t1 = ((long double)box.hi[k] - p) / d;
        if (t0 > t1)
            std::swap(t0, t1);
        enter = std::max(enter, t0);
        exit = std::min(exit, t1);
    }
}

using rt_doctest::problems; // the failures of one kind in a loop, and the first in words

/// A ray and its interval in words: "(-5, 0, 0) + t (1, 0, 0), t in [0, inf]".
std::string ray_words(const vec3& o, const vec3& d, real tmin, real tmax)
{
    std::ostringstream out;
    out << rt_doctest::text(o) << " + t " << rt_doctest::text(d) << ", t in [" << tmin << ", " << tmax << "]";
    return out.str();
}

/// Same hit: t, shape, primitive (for a mesh), point, normals, material.
bool same_hit(const rt::scene& s, const rt::hit_record& a, const rt::hit_record& b)
{
    const bool mesh = a.shape < s.shapes.size() && std::holds_alternative<rt::mesh>(s.shapes[a.shape]);
    return a.t == b.t && a.shape == b.shape && (!mesh || a.primitive == b.primitive) && a.point == b.point &&
           a.normal == b.normal && a.geometric_normal == b.geometric_normal && a.material == b.material &&
           a.front_face == b.front_face;
}

} // namespace

// =============================================================================
// The slab test
// =============================================================================

TEST_CASE("the slab test, hits and misses worked out by hand: axis-parallel rays, -0, the origin inside, tmin and tmax")
{
    const rt::aabb box = box_of(vec3(-1, -1, -1), vec3(1, 2, 3));
    const real zero = 0, minus_zero = -real(0);
    real tnear = 0;
    std::string asked; // the last ray asked about, in words
    auto hits = [&](const vec3& o, const vec3& d, real tmin = 0, real tmax = inf) {
        tnear = -42;
        asked = ray_words(o, d, tmin, tmax);
        return rt::hit_box_textbook(box, rt::ray{o, d}, tmin, tmax, tnear);
    };
    {
        INFO("the box is [-1, 1] x [-1, 2] x [-1, 3], closed; a hit sets tnear to where the ray enters it");
        CHECK_MESSAGE(hits({-5, 0, 0}, {1, zero, zero}), "expected " << asked << " to enter the box at t = 4, found a miss");
        CHECK_MESSAGE(tnear == 4, "expected tnear = 4 for " << asked << ", found " << tnear);
        CHECK_MESSAGE(hits({-5, 0, 0}, {2, zero, zero}), // t counts lengths of d
                      "expected " << asked << " to enter the box at t = 2 (t counts lengths of d), found a miss");
        CHECK_MESSAGE(tnear == 2, "expected tnear = 2 for " << asked << ", found " << tnear);
        CHECK_MESSAGE(hits({-5, 0.5f, 1}, {1, minus_zero, minus_zero}), // -0: 1/d is -inf, the ray stays in those slabs
                      "expected " << asked << " to enter the box at t = 4 (d.y = d.z = -0: 1 / -0 = -inf, and the ray "
                                              "stays inside the y and z slabs), found a miss");
        CHECK_MESSAGE(tnear == 4, "expected tnear = 4 for " << asked << ", found " << tnear);
        CHECK_MESSAGE(hits({0, 0, 9}, {zero, minus_zero, -3}),
                      "expected " << asked << " to enter the box at t = 2 (z = 3), found a miss");
        CHECK_MESSAGE(tnear == 2, "expected tnear = 2 for " << asked << ", found " << tnear);
        CHECK_MESSAGE(hits({-3, -3, -3}, {1, 1, 1}), // through the corner region: enters at x = y = z = -1
                      "expected " << asked << " to enter the box at its corner (-1, -1, -1), t = 2, found a miss");
        CHECK_MESSAGE(tnear == 2, "expected tnear = 2 for " << asked << ", found " << tnear);
        CHECK_MESSAGE(hits({4, 5, 6}, {-1, -1, -1}), // from the far side: enters at x = 1, y = 2, z = 3 at t = 3
                      "expected " << asked << " to enter the box at its corner (1, 2, 3), t = 3, found a miss");
        CHECK_MESSAGE(tnear == 3, "expected tnear = 3 for " << asked << ", found " << tnear);
    }
    {
        INFO("misses: beside the box, pointing away, parallel outside a slab with +0 or -0");
        CHECK_FALSE_MESSAGE(hits({-5, 2.5f, 0}, {1, zero, zero}),
                            "expected " << asked << " to miss (y = 2.5, above the box), found a hit at tnear = " << tnear);
        CHECK_MESSAGE(tnear == -42, "expected a miss to leave tnear as it was (-42), found " << tnear);
        CHECK_FALSE_MESSAGE(hits({-5, 0, 0}, {-1, zero, zero}),
                            "expected " << asked << " to miss (it points away from the box), found a hit at tnear = "
                                        << tnear);
        CHECK_FALSE_MESSAGE(hits({-5, 0, 4}, {1, zero, minus_zero}),
                            "expected " << asked << " to miss (z = 4, beside the box, d.z = -0), found a hit at tnear = "
                                        << tnear);
        CHECK_FALSE_MESSAGE(hits({0, -3, 0}, {minus_zero, minus_zero, 1}),
                            "expected " << asked << " to miss (y = -3, below the box, d.x = d.y = -0), found a hit at "
                                                    "tnear = "
                                        << tnear);
        CHECK_FALSE_MESSAGE(hits({-3, -3, -3}, {1, -1, 1}),
                            "expected " << asked << " to miss (y falls away from the box), found a hit at tnear = "
                                        << tnear);
    }
    INFO("the interval [tmin, tmax]: an origin inside enters at tmin; the box before tmin or beyond tmax is missed");
    CHECK_MESSAGE(hits({0, 0, 0}, {1, 1, 1}, real(0.25)),
                  "expected " << asked << " (from inside the box) to hit, entering at tmin = 0.25; found a miss");
    CHECK_MESSAGE(tnear == real(0.25), "expected tnear = 0.25 for " << asked << ", found " << tnear);
    CHECK_MESSAGE(hits({0, 0, 0}, {1, 1, 1}), "expected " << asked << " (from inside the box) to hit, entering at "
                                                                       "tmin = 0; found a miss");
    CHECK_MESSAGE(tnear == 0, "expected tnear = 0 for " << asked << ", found " << tnear);
    CHECK_FALSE_MESSAGE(hits({-5, 0, 0}, {1, zero, zero}, 0, 3), // it enters at 4
                        "expected " << asked << " to miss: the ray enters the box at t = 4, beyond tmax = 3; found a "
                                                "hit at tnear = "
                                    << tnear);
    CHECK_FALSE_MESSAGE(hits({-5, 0, 0}, {1, zero, zero}, 7), // it leaves at 6
                        "expected " << asked << " to miss: the ray leaves the box at t = 6, before tmin = 7; found a "
                                                "hit at tnear = "
                                    << tnear);
    CHECK_MESSAGE(hits({-5, 0, 0}, {1, zero, zero}, 5, 5.5f),
                  "expected " << asked << " to hit, entering at tmin = 5 (the ray is inside the box from t = 4 to 6); "
                                          "found a miss");
    CHECK_MESSAGE(tnear == 5, "expected tnear = 5 for " << asked << ", found " << tnear);
    CHECK_FALSE_MESSAGE(hits({5, 0, 0}, {1, zero, zero}), // behind the ray
                        "expected " << asked << " to miss: the box is behind the origin; found a hit at tnear = "
                                    << tnear);
}

TEST_CASE("the slab test finds no hit in the empty box")
{
    const rt::aabb empty; // lo = +inf, hi = -inf
    real tnear = -42;
    CHECK_FALSE_MESSAGE(rt::hit_box_textbook(empty, rt::ray{vec3(0), vec3(1, 2, 3)}, 0, inf, tnear),
                        "expected a miss in the empty box (lo = +inf, hi = -inf), found a hit at tnear = " << tnear);
    CHECK_FALSE_MESSAGE(rt::hit_box_textbook(empty, rt::ray{vec3(0), vec3(1, 0, -real(0))}, 0, inf, tnear),
                        "expected a miss in the empty box for the direction (1, 0, -0), found a hit at tnear = "
                            << tnear);
    CHECK_MESSAGE(tnear == -42, "expected a miss to leave tnear as it was (-42), found " << tnear);
}

TEST_CASE("the slab test on random boxes and rays agrees with the exact interval where the ray clears the boundary")
{
    std::mt19937 random(14);
    std::uniform_real_distribution<real> pos(-10, 10), size(real(0.01), 5), scale(real(0.001), 100);
    std::size_t hits = 0, misses = 0, checked = 0;
    for (int k = 0; k < 20000; ++k) {
        const real lx = pos(random);
        const real ly = pos(random);
        const real lz = pos(random);
        const real sx = size(random);
        const real sy = size(random);
        const real sz = size(random);
        const rt::aabb box = box_of(vec3(lx, ly, lz), vec3(lx + sx, ly + sy, lz + sz));
        const real ox = pos(random);
        const real oy = pos(random);
        const real oz = pos(random);
        const real tx = pos(random);
        const real ty = pos(random);
        const real tz = pos(random);
        const real stretch = scale(random);
        // half the rays aimed at a point of the box (hits), half anywhere (mostly misses)
        const vec3 aim = k % 2 == 0 ? box.lo + (vec3(tx, ty, tz) + vec3(10)) / real(20) * box.extent() : vec3(tx, ty, tz);
        rt::ray r{vec3(ox, oy, oz), (aim - vec3(ox, oy, oz)) * stretch};
        if (r.direction.x == 0 || r.direction.y == 0 || r.direction.z == 0)
            continue;
        long double enter = 0, exit = 0;
        exact_interval(box, r, enter, exit);
        enter = std::max(enter, 0.0L);
        // clear of the boundary: the overlap (or the gap) is a thousandth of the distance
        const long double margin = 1e-3L * (std::fabs(enter) + std::fabs(exit) + 1e-3L);
        real tnear = -42;
        const bool hit = rt::hit_box_textbook(box, r, 0, inf, tnear);
        if (exit - enter > margin) {
            ++checked;
            ++hits;
            CAPTURE(r);
            CAPTURE(box);
            REQUIRE_MESSAGE(hit, "expected a hit: the ray is inside the box from t = "
                                     << double(enter) << " to t = " << double(exit) << " (exact); found a miss");
            CHECK_MESSAGE(std::fabs((long double)tnear - enter) <= 1e-4L * (enter + 1e-6L),
                          "expected tnear = " << double(enter) << " (where the ray enters the box, exact), found "
                                              << tnear);
        } else if (enter - exit > margin) {
            ++checked;
            ++misses;
            CAPTURE(r);
            CAPTURE(box);
            REQUIRE_FALSE_MESSAGE(hit, "expected a miss: for t >= 0 the ray is never inside all three slabs at once "
                                       "(it would be from t = "
                                           << double(enter) << " to t = " << double(exit)
                                           << ", exact); found a hit at tnear = " << tnear);
        }
    }
    MESSAGE(checked << " rays checked: " << hits << " clear hits, " << misses << " clear misses");
    CHECK(hits > 1000);
    CHECK(misses > 1000);
}

// =============================================================================
// Building the groups
// =============================================================================

namespace {

/// Checks every promise of build_groups on `g` built from `items`.
void check_groups(const rt::groups& g, const std::vector<rt::group_item>& items, std::size_t leaf_size)
{
    CAPTURE(leaf_size);
    REQUIRE_MESSAGE(g.items.size() == items.size(),
                    "expected g.items to be the " << items.size() << " items given, found " << g.items.size());
    for (std::size_t i = 0; i < items.size(); ++i) {
        INFO("g.items is the list of items given, in the same order; item " << i);
        REQUIRE(g.items[i].shape == items[i].shape);
        REQUIRE(g.items[i].primitive == items[i].primitive);
    }
    REQUIRE_MESSAGE(g.order.size() == items.size(),
                    "expected g.order to list each of the " << items.size() << " items once, found " << g.order.size()
                                                            << " entries");
    if (items.empty()) {
        CHECK_MESSAGE(g.nodes.empty(), "expected no nodes for no items, found " << g.nodes.size());
        return;
    }
    REQUIRE_MESSAGE(!g.nodes.empty(), "expected a root node (node 0) for " << items.size() << " items, found no nodes");
    REQUIRE_MESSAGE(g.nodes[0].first == 0, "expected the root (node 0) to start at order[0], found first = "
                                               << g.nodes[0].first);
    REQUIRE_MESSAGE(g.nodes[0].count == items.size(), "expected the root (node 0) to hold all " << items.size()
                                                          << " items, found count = " << g.nodes[0].count);
    // walk the tree from the root: every node reached once, every item in one leaf
    std::vector<int> in_leaves(items.size(), 0), reached(g.nodes.size(), 0);
    std::vector<std::uint32_t> to_do{0};
    problems bad_boxes, bad_splits, bad_leaves, bad_children;
    while (!to_do.empty()) {
        const std::uint32_t index = to_do.back();
        to_do.pop_back();
        REQUIRE_MESSAGE(index < g.nodes.size(), "expected a child index below " << g.nodes.size() << " (the number of "
                                                "nodes), found " << index);
        REQUIRE_MESSAGE(reached[index] == 0, "expected a tree, found node " << index << " the child of two nodes");
        reached[index] = 1;
        const rt::group_node& node = g.nodes[index];
        REQUIRE_MESSAGE(std::size_t(node.first) + node.count <= g.order.size(),
                        "expected node " << index << "'s items, order[first .. first + count), inside g.order (size "
                                         << g.order.size() << "), found first = " << node.first << ", count = "
                                         << node.count);
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
            REQUIRE_MESSAGE(g.order[k] < items.size(), "expected an item index below " << items.size() << " in order["
                                                                                       << k << "], found " << g.order[k]);
            if (!encloses(node.box, items[g.order[k]].box))
                bad_boxes.add([&](std::ostream& o) {
                    o << "node " << index << "'s box " << rt_doctest::text(node.box) << " does not enclose item "
                      << g.order[k] << "'s box " << rt_doctest::text(items[g.order[k]].box);
                });
        }
        if (node.leaf()) {
            if (!(node.count >= 1 && node.count <= leaf_size))
                bad_leaves.add([&](std::ostream& o) { o << "leaf " << index << " holds " << node.count << " items"; });
            for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
                ++in_leaves[g.order[k]];
            continue;
        }
        REQUIRE_MESSAGE(node.left < g.nodes.size(), "expected node " << index << "'s left child below " << g.nodes.size()
                                                                     << ", found " << node.left);
        REQUIRE_MESSAGE(node.right < g.nodes.size(), "expected node " << index << "'s right child below "
                                                                      << g.nodes.size() << ", found " << node.right);
        const rt::group_node& left = g.nodes[node.left];
        const rt::group_node& right = g.nodes[node.right];
        // the median split: count / 2 to the left, the rest to the right, in order
        if (!(node.count > leaf_size && left.first == node.first && left.count == node.count / 2 &&
              right.first == node.first + node.count / 2 && right.count == node.count - node.count / 2))
            bad_children.add([&](std::ostream& o) {
                o << "node " << index << " (first " << node.first << ", count " << node.count
                  << ") is split into (first " << left.first << ", count " << left.count << ") and (first "
                  << right.first << ", count " << right.count << ")";
            });
        if (!(encloses(node.box, left.box) && encloses(node.box, right.box)))
            bad_boxes.add([&](std::ostream& o) {
                o << "node " << index << "'s box " << rt_doctest::text(node.box)
                  << " does not enclose its children's boxes " << rt_doctest::text(left.box) << " and "
                  << rt_doctest::text(right.box);
            });
        // along an axis where the centroids spread the most, no left centroid beyond a right one
        rt::aabb centroids;
        for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
            centroids.grow(items[g.order[k]].centroid);
        const vec3 spread = centroids.extent();
        const real widest = std::max(spread.x, std::max(spread.y, spread.z));
        bool separated = false;
        for (int axis = 0; axis < 3; ++axis) {
            if (spread[axis] != widest)
                continue;
            real left_max = -inf, right_min = inf;
            for (std::uint32_t k = left.first; k < left.first + left.count; ++k)
                left_max = std::max(left_max, items[g.order[k]].centroid[axis]);
            for (std::uint32_t k = right.first; k < right.first + right.count; ++k)
                right_min = std::min(right_min, items[g.order[k]].centroid[axis]);
            separated = separated || left_max <= right_min;
        }
        if (!separated)
            bad_splits.add([&](std::ostream& o) {
                const char* const axis_names[] = {"x", "y", "z"};
                std::string widest_axes;
                for (int axis = 0; axis < 3; ++axis)
                    if (spread[axis] == widest)
                        widest_axes += std::string(widest_axes.empty() ? "" : " or ") + axis_names[axis];
                o << "node " << index << " (first " << node.first << ", count " << node.count
                  << "): its centroids spread " << rt_doctest::text(spread) << ", widest along " << widest_axes
                  << ", and along it a centroid of the left child lies beyond one of the right";
            });
        to_do.push_back(node.left);
        to_do.push_back(node.right);
    }
    problems not_once;
    for (std::size_t i = 0; i < in_leaves.size(); ++i)
        if (in_leaves[i] != 1)
            not_once.add([&](std::ostream& o) { o << "item " << i << " is in " << in_leaves[i] << " leaves"; });
    CHECK_MESSAGE(not_once.count == 0, "expected every item in exactly one leaf, found "
                                           << not_once.count << " that are not; the first: " << not_once.first);
    CHECK_MESSAGE(bad_leaves.count == 0, "expected every leaf to hold 1 to leaf_size items, found "
                                             << bad_leaves.count << " that do not; the first: " << bad_leaves.first);
    CHECK_MESSAGE(bad_children.count == 0,
                  "expected every inner node to have more than leaf_size items, count / 2 of them to the left child "
                  "(first, count / 2) and the rest to the right (first + count / 2, count - count / 2); found "
                      << bad_children.count << " that do not; the first: " << bad_children.first);
    CHECK_MESSAGE(bad_boxes.count == 0, "expected each node's box to enclose its items' boxes and its children's "
                                        "boxes, found "
                                            << bad_boxes.count << " that do not; the first: " << bad_boxes.first);
    CHECK_MESSAGE(bad_splits.count == 0, "expected the split at the median along the longest axis of the centroids' "
                                         "box (sort the node's items by their centroids along it), found "
                                             << bad_splits.count << " that are not; the first: " << bad_splits.first);
    std::size_t unreached = 0;
    for (int n : reached)
        unreached += n == 1 ? 0 : 1;
    CHECK_MESSAGE(unreached == 0, "expected every node in the tree (reached from the root), found "
                                      << unreached << " of " << g.nodes.size() << " that are not"); // no node outside the tree
}

} // namespace

TEST_CASE("the groups hold every item in exactly one leaf, boxes enclose their children, the split is at the median")
{
    std::mt19937 random(41);
    const rt::scene s = rt_test::random_scene(random, 150, 300, true);
    const std::vector<rt::group_item> items = rt::group_items(s);
    for (const std::size_t leaf_size : {std::size_t(1), std::size_t(2), std::size_t(4), std::size_t(7)})
        check_groups(rt::build_groups(items, leaf_size), items, leaf_size);
    // the default is a few items a leaf
    check_groups(rt::build_groups(items), items, 4);
}

TEST_CASE("the groups of small and degenerate lists: none, one item, items at the same place")
{
    check_groups(rt::build_groups({}, 4), {}, 4);
    rt::scene one;
    one.shapes.emplace_back(rt::sphere{vec3(1, 2, 3), 1, 0});
    const std::vector<rt::group_item> single = rt::group_items(one);
    const rt::groups g = rt::build_groups(single, 4);
    check_groups(g, single, 4);
    REQUIRE_MESSAGE(g.nodes.size() == 1, "expected one node (a leaf) for one item, found " << g.nodes.size());
    CHECK_MESSAGE(g.nodes[0].leaf(), "expected the one node to be a leaf (left = right = 0), found children "
                                         << g.nodes[0].left << " and " << g.nodes[0].right);
    // twenty spheres at one place: the centroids do not spread at all, the median still splits by count
    rt::scene same;
    for (int k = 0; k < 20; ++k)
        same.shapes.emplace_back(rt::sphere{vec3(0), real(1 + k), 0});
    const std::vector<rt::group_item> stacked = rt::group_items(same);
    check_groups(rt::build_groups(stacked, 2), stacked, 2);
}

// =============================================================================
// The closest hit over the groups
// =============================================================================

TEST_CASE("the closest hit over groups built by hand: a box entered a rounding error beyond a tied hit is still visited")
{
    // Two copies of one triangle in the plane x = 1: items 0 and 1, a tie at every
    // ray's hit, which item 1 (the later) wins. The root's left child holds item 0
    // in a box that starts at x = 0, its right child item 1 in the triangle's own
    // box, whose near face x = 1 holds the triangle: in exact arithmetic a ray
    // enters that box exactly where it hits the triangle. Computed, the entry
    // (hit_box_robust's t) and the hit's t (the watertight test's) are rounded
    // apart, and for some rays the entry comes out above the hit, within the slab
    // test's own margin (t_hit < entry <= t_hit * slab_robust_far_factor). Only
    // those rays are kept here. The left child is entered first (x = 0), finds the
    // hit, and then item 1's box starts, as computed, "beyond the closest hit so
    // far": a traversal that skips it on `entry > closest` answers item 0.
    rt::triangle tri;
    tri.a = vec3(1, -4, -4);
    tri.b = vec3(1, 4, -4);
    tri.c = vec3(1, 0, 4);
    rt::scene s;
    s.shapes.emplace_back(tri);
    s.shapes.emplace_back(tri);
    rt::groups g;
    g.items = rt::group_items(s);
    g.order = {0, 1};
    const rt::aabb own = g.items[1].box; // x from 1 to 1
    rt::aabb wide = own;
    wide.lo.x = 0;
    g.nodes = {rt::group_node{wide, 0, 2, 1, 2}, rt::group_node{wide, 0, 1, 0, 0}, rt::group_node{own, 1, 1, 0, 0}};
    std::mt19937 random(2013);
    std::uniform_real_distribution<float> spread(-1, 1);
    int rays = 0;
    problems skipped, earlier, missed;
    for (int k = 0; k < 20000 && rays < 40; ++k) {
        const real ox = -3 + spread(random), oy = spread(random), oz = spread(random);
        const real dy = real(0.3) * spread(random), dz = real(0.3) * spread(random);
        const rt::ray r{vec3(ox, oy, oz), vec3(1, dy, dz)};
        rt::hit_record at;
        real entry = 0;
        if (!rt::hit_group_item(s, g.items[1], r, 0, inf, at) || !rt::hit_box_robust(own, r, 0, inf, entry) ||
            !(entry > at.t && entry <= at.t * rt::slab_robust_far_factor))
            continue; // not a ray whose entry rounds above the hit
        ++rays;
        std::vector<std::uint32_t> tested;
        auto recording = [&](std::uint32_t i, const rt::ray& q, real tmin, real tmax, rt::hit_record& rec) {
            tested.push_back(i);
            return rt::hit_group_item(s, g.items[i], q, tmin, tmax, rec);
        };
        rt::hit_record rec;
        const bool hit = rt::closest_hit_groups(g, r, 0, inf, rec, recording);
        const bool item_1_tested = std::find(tested.begin(), tested.end(), 1u) != tested.end();
        auto describe = [&](std::ostream& o) {
            o << ray_words(r.origin, r.direction, 0, inf) << ": both items hit at t = "
              << std::setprecision(std::numeric_limits<real>::max_digits10) << at.t
              << ", item 1's box entered at t = " << entry << " (as hit_box_robust computes it)";
        };
        if (!hit)
            missed.add(describe);
        else if (rec.shape != 1 && !item_1_tested)
            skipped.add(describe);
        else if (rec.shape != 1)
            earlier.add(describe);
    }
    REQUIRE_MESSAGE(rays >= 10, "expected at least 10 rays whose entry into item 1's box rounds above the hit, found "
                                    << rays << " (a fault of the test, not of your code)");
    CHECK_MESSAGE(missed.count == 0, "expected a hit (items 0 and 1, the same triangle) for every ray, found none for "
                                         << missed.count << " of " << rays << "; the first: " << missed.first);
    CHECK_MESSAGE(skipped.count == 0,
                  "expected item 1 (the later of two at an equal t), found item 0 for "
                      << skipped.count << " of " << rays << " rays, and item 1 never tested; the first: "
                      << skipped.first
                      << ". Item 1's box was skipped because its entry, as computed, lies a rounding error beyond the "
                         "closest hit so far, where in exact arithmetic the two are equal: the box skipped under "
                         "rounding (the tie rule is not the cause: item 1 was never asked). Skip a box only when it "
                         "starts beyond closest * rt::slab_robust_far_factor, the slab test's own margin: "
                         "`if (t_enter > closest * rt::slab_robust_far_factor) continue;`");
    CHECK_MESSAGE(earlier.count == 0, "expected item 1 (the later of two at an equal t), found item 0 for "
                                          << earlier.count << " of " << rays << " rays, with item 1 tested; the first: "
                                          << earlier.first
                                          << ". The tie rule: at an equal t keep the later item (the larger index "
                                             "into g.items), so a hit at t == closest from a later item replaces "
                                             "the one kept");
}

TEST_CASE("the closest hit over the groups is the closest hit of the list on random scenes and rays, ties included")
{
    for (const unsigned seed : {3u, 17u}) {
        std::mt19937 random(seed);
        const rt::scene s = rt_test::random_scene(random, seed == 3 ? 300 : 150, seed == 3 ? 600 : 300, seed == 17);
        const std::vector<rt::ray> rays = rt_test::random_rays(random, 1500);
        for (const std::size_t leaf_size : {std::size_t(1), std::size_t(4)}) {
            const rt::groups g = rt::build_groups(rt::group_items(s), leaf_size);
            auto hit_item = [&](std::uint32_t i, const rt::ray& r, real tmin, real tmax, rt::hit_record& rec) {
                return rt::hit_group_item(s, g.items[i], r, tmin, tmax, rec);
            };
            std::size_t hits = 0, different = 0;
            for (std::size_t k = 0; k < rays.size(); ++k) {
                const real tmax = k % 4 == 3 ? real(6) : inf; // some rays end early
                rt::hit_record from_list, from_groups;
                from_groups.t = -42;
                const bool a = rt::closest_hit_list(s, rays[k], 0, tmax, from_list);
                const bool b = rt::closest_hit_groups(g, rays[k], 0, tmax, from_groups, hit_item);
                hits += a ? 1 : 0;
                if (a != b || (a && !same_hit(s, from_list, from_groups)) || (!b && from_groups.t != -42)) {
                    if (different == 0) {
                        CAPTURE(seed);
                        CAPTURE(leaf_size);
                        CAPTURE(rays[k]);
                        CAPTURE(from_list);
                        CAPTURE(from_groups);
                        // the first difference, in full
                        CHECK_MESSAGE(a == b, "expected " << std::string(a ? "a hit (the list's)" : "no hit")
                                                          << ", found " << std::string(b ? "a hit" : "none"));
                        // at an equal t, whether the list's item was asked at all tells a box skipped
                        // under rounding from the tie rule forgotten
                        // a hit nearer than the list's, or a later item at the same t, is the
                        // list's mistake: from_list is the student's closest_hit_list
                        std::string cause;
                        const bool later = std::make_pair(from_groups.shape, from_groups.primitive) >
                                           std::make_pair(from_list.shape, from_list.primitive);
                        const bool list_wrong =
                            a && b && (from_groups.t < from_list.t || (from_list.t == from_groups.t && later));
                        if (a && b && from_groups.t < from_list.t)
                            cause = "; your groups found a nearer hit than your list: closest_hit_list returned a "
                                    "hit that is not the closest (the last one found?): pass the closest t so far as "
                                    "tmax to the next shape";
                        else if (a && b && from_list.t == from_groups.t && later)
                            cause = "; a tie, and your list kept the earlier shape: at an equal t closest_hit_list "
                                    "keeps the later shape (the tie rule)";
                        else if (a && b && from_list.t == from_groups.t) {
                            const bool mesh = std::holds_alternative<rt::mesh>(s.shapes[from_list.shape]);
                            bool asked = false;
                            auto asking = [&](std::uint32_t i, const rt::ray& r, real t0, real t1, rt::hit_record& out) {
                                asked = asked || (g.items[i].shape == from_list.shape &&
                                                  (!mesh || g.items[i].primitive == from_list.primitive));
                                return rt::hit_group_item(s, g.items[i], r, t0, t1, out);
                            };
                            rt::hit_record again;
                            rt::closest_hit_groups(g, rays[k], 0, tmax, again, asking);
                            cause = asked ? "; a tie, and the list's item was tested: keep the later item at an "
                                            "equal t (the tie rule)"
                                          : "; a tie, and the list's item was never tested: its box was skipped, "
                                            "entered (as computed) a rounding error beyond the closest hit so far: "
                                            "skip a box only when it starts beyond closest * "
                                            "rt::slab_robust_far_factor";
                        }
                        CHECK_MESSAGE(same_hit(s, from_list, from_groups),
                                      std::string(list_wrong ? "your closest_hit_list (from_list) and your groups "
                                                               "(from_groups) disagree, and the list is wrong"
                                                  : a && b ? "expected the list's closest hit (from_list), found "
                                                           "another (from_groups): the nearest hit, and at an equal t "
                                                           "the later item (from_list is your closest_hit_list: if "
                                                           "stage04_triangle's cases fail too, fix it first)"
                                                         : "expected the same records: on a miss closest_hit_groups "
                                                           "leaves the record as it was (t = -42)") << cause);
                    }
                    ++different;
                }
            }
            MESSAGE("seed " << seed << ", leaf size " << leaf_size << ": " << rays.size() << " rays, " << hits
                            << " hits, " << different << " differ from the list");
            CHECK(hits > 100);
            CHECK_MESSAGE(different == 0, "expected closest_hit_groups to answer as closest_hit_list on all "
                                              << rays.size() << " rays, found " << different << " that differ");
        }
    }
}

TEST_CASE("a ray that misses the root box tests no item, and along a row of spheres only the nearest is tested")
{
    rt::scene s; // 64 unit spheres along x at x = 0, 3, 6, ..., 189
    for (int k = 0; k < 64; ++k)
        s.shapes.emplace_back(rt::sphere{vec3(real(3 * k), 0, 0), 1, 0});
    const rt::groups g = rt::build_groups(rt::group_items(s), 1);
    std::size_t tests = 0;
    auto counting = [&](std::uint32_t i, const rt::ray& r, real tmin, real tmax, rt::hit_record& rec) {
        ++tests;
        return rt::hit_group_item(s, g.items[i], r, tmin, tmax, rec);
    };
    rt::hit_record rec;
    rec.t = -42;
    {
        INFO("above the row, parallel to it: the root box is missed, no item is tested");
        CHECK_FALSE_MESSAGE(rt::closest_hit_groups(g, rt::ray{vec3(-10, 5, 0), vec3(1, 0, 0)}, 0, inf, rec, counting),
                            "expected no hit, found shape " << rec.shape << " at t = " << rec.t);
        CHECK_MESSAGE(tests == 0, "expected no item tested, found " << tests);
        CHECK_MESSAGE(rec.t == -42, "expected the record untouched on a miss (t = -42), found t = " << rec.t);
    }
    {
        INFO("across the row between two spheres (x = 1.5): inside the root box, outside every leaf's");
        CHECK_FALSE_MESSAGE(rt::closest_hit_groups(g, rt::ray{vec3(1.5f, -10, 0), vec3(0, 1, 0)}, 0, inf, rec, counting),
                            "expected no hit, found shape " << rec.shape << " at t = " << rec.t);
        CHECK_MESSAGE(tests == 0, "expected no item tested (test an item only when its leaf's box is hit), found "
                                      << tests);
    }
    {
        INFO("along the row from the left: the nearer child first, so sphere 0 is hit first and every other box, "
             "which starts beyond that hit, is skipped: one item tested");
        tests = 0;
        REQUIRE_MESSAGE(rt::closest_hit_groups(g, rt::ray{vec3(-10, 0, 0), vec3(1, 0, 0)}, 0, inf, rec, counting),
                        "expected a hit on sphere 0 at t = 9, found none");
        CHECK(rec.shape == 0);
        CHECK(rec.t == 9);
        CHECK_MESSAGE(tests == 1, "expected 1 item tested, found " << tests);
    }
    {
        INFO("along the row from the right: sphere 63 first, one item tested");
        tests = 0;
        REQUIRE_MESSAGE(rt::closest_hit_groups(g, rt::ray{vec3(200, 0, 0), vec3(-1, 0, 0)}, 0, inf, rec, counting),
                        "expected a hit on sphere 63 at t = 10, found none");
        CHECK(rec.shape == 63);
        CHECK(rec.t == 200 - 189 - 1);
        CHECK_MESSAGE(tests == 1, "expected 1 item tested, found "
                                      << tests
                                      << ": visit the nearer child first (push the farther one first), so that "
                                         "the nearest item's hit skips the boxes beyond it");
    }
    INFO("an empty scene: no groups, no hit");
    const rt::groups none = rt::build_groups({}, 4);
    tests = 0;
    CHECK_FALSE_MESSAGE(rt::closest_hit_groups(none, rt::ray{vec3(0), vec3(1, 0, 0)}, 0, inf, rec, counting),
                        "expected no hit (there are no nodes), found shape " << rec.shape << " at t = " << rec.t);
    CHECK_MESSAGE(tests == 0, "expected no item tested, found " << tests);
}

TEST_CASE("the closest hit over groups built by hand: nearer child first, farther boxes skipped, a tie to the later item")
{
    // closest_hit_groups on its own, whatever build_groups does: three unit
    // spheres on the x axis at x = 0, 10 and 20; the root's left child holds
    // sphere 2 (the far one), its right child spheres 0 and 1, so a ray from
    // the left must visit the right child first although it comes second
    rt::scene s;
    for (const real x : {real(0), real(10), real(20)})
        s.shapes.emplace_back(rt::sphere{vec3(x, 0, 0), 1, 0});
    rt::groups g;
    g.items = rt::group_items(s);
    g.order = {2, 0, 1};
    const rt::aabb all = box_of(vec3(-1.5f, -1.5f, -1.5f), vec3(21.5f, 1.5f, 1.5f));
    g.nodes = {rt::group_node{all, 0, 3, 1, 2},
               rt::group_node{box_of(vec3(18.5f, -1.5f, -1.5f), vec3(21.5f, 1.5f, 1.5f)), 0, 1, 0, 0},
               rt::group_node{box_of(vec3(-1.5f, -1.5f, -1.5f), vec3(11.5f, 1.5f, 1.5f)), 1, 2, 0, 0}};
    std::vector<std::uint32_t> tested;
    auto recording = [&](std::uint32_t i, const rt::ray& r, real tmin, real tmax, rt::hit_record& rec) {
        tested.push_back(i);
        return rt::hit_group_item(s, g.items[i], r, tmin, tmax, rec);
    };
    rt::hit_record rec;
    REQUIRE_MESSAGE(rt::closest_hit_groups(g, rt::ray{vec3(-10, 0, 0), vec3(1, 0, 0)}, 0, inf, rec, recording),
                    "expected a hit: the ray along the x axis meets all three spheres");
    CHECK_MESSAGE(rec.shape == 0, "expected sphere 0 (t = 9), the nearest, found shape " << rec.shape);
    CHECK(rec.t == 9);
    const bool far_child_skipped = std::find(tested.begin(), tested.end(), 2u) == tested.end();
    CHECK_MESSAGE(far_child_skipped, "expected the left child (sphere 2, whose box starts at t = 28.5) never "
                                     "visited: the right child's box starts nearer (t = 8.5), is visited first, "
                                     "and its hit at t = 9 ends the search; "
                                         << tested.size() << " item(s) tested");

    {
        INFO("tmax before every sphere: nothing hit, the record untouched");
        tested.clear();
        rec.t = -42;
        CHECK_FALSE_MESSAGE(rt::closest_hit_groups(g, rt::ray{vec3(-10, 0, 0), vec3(1, 0, 0)}, 0, 5, rec, recording),
                            "expected no hit with tmax = 5 (the nearest sphere is at t = 9), found shape "
                                << rec.shape << " at t = " << rec.t);
        CHECK_MESSAGE(rec.t == -42, "expected the record untouched on a miss (t = -42), found t = " << rec.t);
    }

    INFO("two items at the same t (the same sphere twice, items 1 and 2): the later item in scene order wins");
    rt::scene twice;
    twice.shapes.emplace_back(rt::sphere{vec3(10, 0, 0), 1, 0});
    twice.shapes.emplace_back(rt::sphere{vec3(0, 0, 0), 1, 0});
    twice.shapes.emplace_back(rt::sphere{vec3(0, 0, 0), 1, 0});
    rt::groups h;
    h.items = rt::group_items(twice);
    h.order = {2, 1, 0};
    h.nodes = {rt::group_node{all, 0, 3, 1, 2},
               rt::group_node{box_of(vec3(-1.5f, -1.5f, -1.5f), vec3(1.5f, 1.5f, 1.5f)), 0, 2, 0, 0},
               rt::group_node{box_of(vec3(8.5f, -1.5f, -1.5f), vec3(11.5f, 1.5f, 1.5f)), 2, 1, 0, 0}};
    auto hit_twice = [&](std::uint32_t i, const rt::ray& r, real tmin, real tmax, rt::hit_record& out) {
        return rt::hit_group_item(twice, h.items[i], r, tmin, tmax, out);
    };
    REQUIRE_MESSAGE(rt::closest_hit_groups(h, rt::ray{vec3(-10, 0, 0), vec3(1, 0, 0)}, 0, inf, rec, hit_twice),
                    "expected a hit at t = 9 (items 1 and 2, the same sphere), found none");
    CHECK(rec.t == 9);
    CHECK_MESSAGE(rec.shape == 2, "expected item 2 (the later of two at t = 9), found shape " << rec.shape);
}
