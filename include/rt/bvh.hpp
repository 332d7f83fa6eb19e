// bvh.hpp - the fast path: a bounding volume hierarchy over packed primitives (stage 04).
//
// The course's group is a list searched from start to end; with n shapes every
// ray pays n intersection tests. A bounding volume hierarchy (BVH) puts the
// shapes in nested axis-aligned boxes, so a ray that misses a box skips all of
// its shapes: about log n box tests instead of n shape tests. This file is the
// engine behind rt::accelerator (intersect.hpp); the readable list is
// rt::closest_hit_list there, and the two return the same hits.
//
// Build (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies",
// IEEE Symposium on Interactive Ray Tracing 2007, sec. 3): top down, a binary
// tree; each node's primitives are sorted into `bins` equal slices of their
// centroids' extent on each axis, and the node is split at the slice boundary
// of least surface area heuristic cost (MacDonald, Booth, "Heuristics for ray
// tracing using space subdivision", The Visual Computer 6(3), 1990):
//     C = C_trav + C_isect (A_L N_L + A_R N_R) / A,
// A the surface areas of the boxes, N the primitive counts; a node becomes a
// leaf when that is cheaper than any split (C_isect N <= C) and holds at most
// max_leaf_size primitives, or when it reaches max_depth. The binary tree is
// then collapsed into 4-wide nodes (see wide_collapser).
//
// Layout, and why:
//  - A node holds the boxes of up to four children, not its own box (as the
//    4-wide BVHs cited at wide_collapser do; Aila and Laine, "Understanding the
//    Efficiency of Ray Traversal on GPUs", HPG 2009, store two): one visit tests four boxes, and
//    a ray visits about half as many nodes as in a binary tree. The boxes are
//    stored plane by plane, bounds[lo x / hi x / lo y / hi y / lo z / hi z][child],
//    so that one 4-wide SIMD instruction treats the same plane of all four
//    children: a visit is 6 loads, 6 subtractions, 6 multiplications and 6
//    min/max, for four boxes. With the references a node is 128 bytes in
//    float, two cache lines, aligned.
//  - A child is an inner node (`child` is its index) or a leaf (`child` is
//    leaf_flag | its first primitive, `count` its primitives). Leaves cost no
//    node of their own. Nodes are stored flat in one array, depth first.
//  - Primitives are copied into one array in leaf order (packed_primitive, 40
//    bytes in float): a leaf's triangles are contiguous, and each carries its
//    corners, not indices into a vertex array, so a test is one memory access.
//  - Per ray, traversal precomputes the reciprocal direction and, per axis,
//    which plane row of a node is met first (the sign of the reciprocal), so a
//    box test is a subtraction and a multiplication per plane, no division and
//    no branch. The watertight test's axis permutation and shear are also
//    precomputed once per ray.
//  - Children are visited nearest first: the hit children are sorted by entry
//    distance, the nearest is entered and the others go on a fixed-size stack
//    with their distances; an entry whose distance is beyond the closest hit
//    found meanwhile is skipped when popped. The stack is a local array: no
//    allocation per ray. any() returns at the first hit (shadow rays), and
//    pushes the children unsorted: their order cannot change its answer.
//  - With SSE2 (every x86-64 compiler, no -march needed) the four boxes are
//    tested in 4-wide registers; elsewhere, and for rt::real = double, the same
//    arithmetic runs one value at a time. Both give identical results.
//
// The slab test is robust (Williams, Barrus, Morley, Shirley, "An Efficient and
// Robust Ray-Box Intersection Algorithm", Journal of Graphics Tools 10(1),
// 2005; Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013):
//  - 1/d is computed as IEEE gives it: +-inf for a zero component, the sign
//    following the sign of zero (-0 gives -inf), so axis-parallel rays and -0
//    need no special case; the near plane of each axis is chosen by the sign
//    of 1/d.
//  - A ray lying in a slab plane gives (plane - o) * inf = 0 * inf = NaN. Each
//    comparison is written so that a NaN leaves the running interval as it was:
//    the ray counts as inside that slab (the box is closed), never as outside,
//    and no NaN reaches a result.
//  - Rounding can make the computed t_far smaller than the computed t_near
//    when the exact values are equal (a ray through a box edge or corner, and
//    a triangle's box is touched by the triangle at its corners). Ize shows the
//    computed values are within gamma_3 of the exact ones, so comparing
//    t_near <= t_far (1 + 2 gamma_3) never culls a box the ray truly meets.
//    The factor is applied to min(t_far, t_max), so a hit at exactly the
//    current closest t is not culled either.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

// RT_BVH_SSE: SSE2 is there (every x86-64 compiler) and rt::real is float.
// Defined here and undefined at the end of this file.
#if (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)) && \
    !(defined(RT_USE_DOUBLE) && RT_USE_DOUBLE)
#define RT_BVH_SSE 1
#else
#define RT_BVH_SSE 0
#endif

#if RT_BVH_SSE
#include <emmintrin.h>
#endif

#include "aabb.hpp"
#include "error.hpp"
#include "hit_record.hpp"
#include "ray.hpp"
#include "rounding.hpp"
#include "sphere.hpp"
#include "triangle.hpp"
#include "vec.hpp"

namespace rt {

// --- primitives laid out for traversal ---------------------------------------

/// Set in packed_primitive::id for a sphere.
constexpr std::uint32_t sphere_flag = 0x80000000u;

/// One primitive as traversal reads it: a triangle's corners a, b, c (v[0..8])
/// or a sphere's centre (v[0..2]) and radius (v[3]); `id` is the primitive's
/// number in scene order, with sphere_flag set for spheres.
struct packed_primitive {
    real v[9];
    std::uint32_t id;
};

inline packed_primitive pack_triangle(const vec3& a, const vec3& b, const vec3& c, std::uint32_t id)
{
    return packed_primitive{{a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z}, id};
}

inline packed_primitive pack_sphere(const sphere& s, std::uint32_t id)
{
    return packed_primitive{{s.center.x, s.center.y, s.center.z, s.radius, 0, 0, 0, 0, 0}, id | sphere_flag};
}

/// A box that contains the primitive. A triangle's box is exact (the min and
/// max of its corners); a sphere's is widened by a few ulps, because c +- R
/// is rounded and the box must not cut the sphere.
inline aabb packed_bounds(const packed_primitive& p)
{
    aabb box;
    if (p.id & sphere_flag) {
        const vec3 c(p.v[0], p.v[1], p.v[2]);
        const real r = p.v[3];
        const vec3 margin = gamma_n(4) * (glm::abs(c) + vec3(r));
        box.lo = c - vec3(r) - margin;
        box.hi = c + vec3(r) + margin;
    } else {
        for (int k = 0; k < 3; ++k)
            box.grow(vec3(p.v[3 * k], p.v[3 * k + 1], p.v[3 * k + 2]));
    }
    return box;
}

/// A hit on a packed primitive: t, the barycentrics (triangles only), the
/// primitive's number in scene order (without sphere_flag) and the packed
/// primitive itself (its corners are in cache: completing the hit record
/// reads them there rather than through the mesh's index arrays).
struct primitive_hit {
    real t = 0;
    real b0 = 0, b1 = 0, b2 = 0;
    std::uint32_t id = 0;
    const packed_primitive* source = nullptr;
};

/// The one rule for "closest": a smaller t wins; at an equal t the later
/// primitive in scene order wins, as in the course's list loop, which passes
/// the closest t so far as tmax and so accepts a later hit at the same t.
/// With it the flat list and the BVH return the same hit whatever the order
/// of their tests.
inline bool replaces(const primitive_hit& candidate, const primitive_hit& best)
{
    return candidate.t < best.t || (candidate.t == best.t && candidate.id > best.id);
}

/// Intersects one packed primitive with the library's default methods: the
/// watertight triangle test and rt::hit_sphere.
inline bool intersect_packed(const packed_primitive& p, const ray& r, const watertight_ray& w, real tmin, real tmax,
                             primitive_hit& hit)
{
    if (p.id & sphere_flag) {
        sphere s;
        s.center = vec3(p.v[0], p.v[1], p.v[2]);
        s.radius = p.v[3];
        hit_record rec;
        if (!hit_sphere(s, r, tmin, tmax, rec))
            return false;
        hit.t = rec.t;
        hit.b0 = hit.b1 = hit.b2 = 0;
        hit.id = p.id & ~sphere_flag;
        hit.source = &p;
        return true;
    }
    triangle_hit h;
    if (!intersect_watertight(w, p.v, tmin, tmax, h))
        return false;
    hit.t = h.t;
    hit.b0 = h.b0;
    hit.b1 = h.b1;
    hit.b2 = h.b2;
    hit.id = p.id;
    hit.source = &p;
    return true;
}

/// The flat list over packed primitives: every primitive tested, the closest
/// kept by replaces(). For scenes too small to pay for a BVH.
inline bool closest_flat(const std::vector<packed_primitive>& prims, const ray& r, real tmin, real tmax,
                         primitive_hit& best)
{
    const watertight_ray w = make_watertight_ray(r);
    bool found = false;
    for (const packed_primitive& p : prims) {
        primitive_hit h;
        if (intersect_packed(p, r, w, tmin, found ? best.t : tmax, h) && (!found || replaces(h, best))) {
            best = h;
            found = true;
        }
    }
    return found;
}

/// Whether any packed primitive is hit in [tmin, tmax].
inline bool any_flat(const std::vector<packed_primitive>& prims, const ray& r, real tmin, real tmax)
{
    const watertight_ray w = make_watertight_ray(r);
    primitive_hit h;
    for (const packed_primitive& p : prims)
        if (intersect_packed(p, r, w, tmin, tmax, h))
            return true;
    return false;
}

// --- the robust slab test ----------------------------------------------------

/// Ize 2013: the computed t_far is scaled by 1 + 2 gamma_3 before it is
/// compared with t_near, so that rounding never culls a box the ray meets.
constexpr real slab_far_factor = 1 + 2 * gamma_n(3);

/// A ray prepared for box tests: its origin, 1/d (+-inf for a +-0
/// component) and, per axis, 1 when 1/d is negative (the near plane is hi).
struct box_ray {
    vec3 origin{0};
    vec3 inv_dir{0};
    int negative[3] = {0, 0, 0};
};

inline box_ray make_box_ray(const ray& r)
{
    box_ray b;
    b.origin = r.origin;
    for (int k = 0; k < 3; ++k) {
        b.inv_dir[k] = real(1) / r.direction[k]; // IEEE: 1/+0 = +inf, 1/-0 = -inf
        b.negative[k] = std::signbit(b.inv_dir[k]) ? 1 : 0;
    }
    return b;
}

/// The robust slab test (see the top of this file): true when the ray meets
/// `box` within [tmin, tmax]; `tnear` is then where it enters. `far_factor`
/// is Ize's 1 + 2 gamma_3; the tests pass 1 to show what goes wrong without it.
inline bool hit_box(const aabb& box, const box_ray& r, real tmin, real tmax, real& tnear,
                    real far_factor = slab_far_factor)
{
    real t0 = tmin, t1 = tmax;
    for (int k = 0; k < 3; ++k) {
        const real near_plane = r.negative[k] ? box.hi[k] : box.lo[k];
        const real far_plane = r.negative[k] ? box.lo[k] : box.hi[k];
        const real t_near = (near_plane - r.origin[k]) * r.inv_dir[k];
        const real t_far = (far_plane - r.origin[k]) * r.inv_dir[k];
        t0 = t_near > t0 ? t_near : t0; // a NaN (ray in this plane) keeps t0
        t1 = t_far < t1 ? t_far : t1;   // a NaN keeps t1
    }
    tnear = t0;
    return t0 <= t1 * far_factor;
}

// --- the hierarchy -----------------------------------------------------------

/// How a BVH is built (see the top of this file). The defaults were chosen by
/// measuring primary rays on the Stanford bunny (docs/stages/04-triangle.md).
struct bvh_options {
    int bins = 16;                    ///< SAH slices per axis and node
    std::size_t max_leaf_size = 8;    ///< a node with more primitives is always split
    real traversal_cost = 1;          ///< C_trav: one node visit
    real intersection_cost = 1;       ///< C_isect: one primitive test
    int max_depth = 60;               ///< a node this deep in the binary tree becomes a leaf
    int threads = 0;                  ///< threads for the build; 0: one per core (the tree is the same)
};

/// What a build produced.
struct bvh_stats {
    std::size_t primitives = 0;
    std::size_t nodes = 0;        ///< 4-wide nodes
    std::size_t leaves = 0;
    std::size_t binary_nodes = 0; ///< inner nodes of the binary tree before collapsing
    int depth = 0;                ///< the deepest leaf: the root's children are at depth 1
    double sah_cost = 0;          ///< the binary tree's SAH cost, in units of one primitive test
};

/// One 4-wide node (see the top of this file): the boxes of up to four
/// children, plane by plane, and their references. 128 bytes in float.
struct alignas(64) bvh_node {
    /// bounds[2 k][c] = lo of child c on axis k, bounds[2 k + 1][c] = hi; an
    /// unused child has the empty box lo = +inf, hi = -inf, which no ray meets.
    real bounds[6][4];
    std::uint32_t child[4];  ///< an inner child's node index, or leaf_flag | its first primitive
    std::uint32_t count[4];  ///< a leaf's number of primitives (0 for inner children)
};

/// Set in bvh_node::child for a leaf.
constexpr std::uint32_t leaf_flag = 0x80000000u;

namespace detail {

/// A primitive during the build: its box, its centroid and where it came from.
struct build_item {
    aabb box;
    vec3 centroid{0};
    std::uint32_t index = 0;
};

inline real half_area(const aabb& box)
{
    if (box.empty())
        return 0;
    const vec3 e = box.extent();
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

/// A child of a binary node: inner (count 0, `index` a binary node) or a leaf
/// (`count` primitives from `index`).
struct binary_child {
    aabb box;
    std::uint32_t index = 0;
    std::uint32_t count = 0;
};

struct binary_node {
    binary_child side[2];
};

/// The binned SAH build of a binary tree (see the top of this file).
///
/// Speed: one pass over a node's primitives bins them on all three axes at
/// once; the two halves of the top of the tree are built on separate threads
/// (bvh_options::threads), each into its own node array, and the arrays are
/// joined in the order a single thread writes them, so the tree is the same
/// whatever the number of threads.
class binary_builder {
public:
    binary_builder(std::vector<build_item>& items, const bvh_options& options, int spare_threads)
        : items_(items), options_(options), spare_threads_(spare_threads),
          bin_count_(std::size_t(std::max(2, std::min(options.bins, 256))))
    {
        for (int axis = 0; axis < 3; ++axis)
            bins_[axis].resize(bin_count_);
        right_cost_.resize(bin_count_);
        right_box_.resize(bin_count_);
    }

    std::vector<binary_node> nodes;
    double sah_cost = 0; ///< the sum of C A over the subtree, before dividing by the root's area

    /// Builds the subtree of items [begin, end) inside `box`; returns it as a child.
    binary_child build(std::size_t begin, std::size_t end, const aabb& box, int depth)
    {
        const std::size_t n = end - begin;
        const real area = half_area(box);
        if (n <= 1 || depth >= options_.max_depth)
            return leaf(begin, n, box, area);

        aabb centroids;
        for (std::size_t i = begin; i < end; ++i)
            centroids.grow(items_[i].centroid);

        aabb left_box, right_box;
        std::size_t middle = begin;
        const split best = find_split(begin, end, centroids);
        if (best.axis < 0) {
            // every centroid is the same point: no plane separates them
            if (n <= options_.max_leaf_size)
                return leaf(begin, n, box, area);
            middle = begin + n / 2;
            for (std::size_t i = begin; i < middle; ++i)
                left_box.grow(items_[i].box);
            for (std::size_t i = middle; i < end; ++i)
                right_box.grow(items_[i].box);
        } else {
            const real split_cost =
                area > 0 ? options_.traversal_cost + options_.intersection_cost * best.cost / area : real(0);
            const real leaf_cost = options_.intersection_cost * real(n);
            if (n <= options_.max_leaf_size && leaf_cost <= split_cost)
                return leaf(begin, n, box, area);
            const int axis = best.axis;
            const real low = centroids.lo[axis];
            const real scale = real(bin_count_) / (centroids.hi[axis] - low);
            const auto first_right = std::partition(
                items_.begin() + std::ptrdiff_t(begin), items_.begin() + std::ptrdiff_t(end),
                [&](const build_item& item) { return bin_of(item.centroid[axis], low, scale) < best.bin; });
            middle = std::size_t(first_right - items_.begin());
            left_box = best.left;
            right_box = best.right;
        }

        const std::size_t index = nodes.size();
        nodes.emplace_back();
        sah_cost += double(options_.traversal_cost) * double(area);
        binary_child left, right;
        if (spare_threads_ > 0 && n >= parallel_threshold) {
            // the right half on a thread of its own, with half of the spare threads
            const int for_right = spare_threads_ / 2 + spare_threads_ % 2 - 1;
            spare_threads_ -= for_right + 1;
            binary_builder right_builder(items_, options_, for_right);
            std::exception_ptr failure;
            std::thread worker([&] {
                try {
                    right = right_builder.build(middle, end, right_box, depth + 1);
                } catch (...) {
                    failure = std::current_exception();
                }
            });
            try {
                left = build(begin, middle, left_box, depth + 1);
            } catch (...) {
                worker.join();
                throw;
            }
            worker.join();
            if (failure)
                std::rethrow_exception(failure);
            // join the arrays: the right subtree's nodes follow the left subtree's
            const std::uint32_t offset = std::uint32_t(nodes.size());
            for (binary_node& node : right_builder.nodes)
                for (binary_child& side : node.side)
                    if (side.count == 0)
                        side.index += offset;
            if (right.count == 0)
                right.index += offset;
            nodes.insert(nodes.end(), right_builder.nodes.begin(), right_builder.nodes.end());
            sah_cost += right_builder.sah_cost;
        } else {
            left = build(begin, middle, left_box, depth + 1);
            right = build(middle, end, right_box, depth + 1);
        }
        nodes[index].side[0] = left;
        nodes[index].side[1] = right;
        binary_child inner;
        inner.box = box;
        inner.index = std::uint32_t(index);
        return inner;
    }

private:
    /// Below this many primitives a subtree is not worth a thread.
    static constexpr std::size_t parallel_threshold = 4096;

    struct bin {
        aabb box;
        std::size_t count = 0;
    };

    struct split {
        int axis = -1;
        std::size_t bin = 0;  ///< the first bin of the right side
        real cost = 0;        ///< A_L N_L + A_R N_R
        aabb left, right;
    };

    std::size_t bin_of(real centroid, real low, real scale) const
    {
        const real slot = (centroid - low) * scale;
        return std::min(bin_count_ - 1, std::size_t(slot > 0 ? slot : real(0)));
    }

    split find_split(std::size_t begin, std::size_t end, const aabb& centroids)
    {
        real low[3], scale[3];
        for (int axis = 0; axis < 3; ++axis) {
            low[axis] = centroids.lo[axis];
            const real extent = centroids.hi[axis] - low[axis];
            scale[axis] = extent > 0 ? real(bin_count_) / extent : real(0); // 0: all in bin 0, never split
            for (bin& b : bins_[axis])
                b = bin{};
        }
        for (std::size_t i = begin; i < end; ++i) { // one pass, three axes
            const build_item& item = items_[i];
            for (int axis = 0; axis < 3; ++axis) {
                bin& b = bins_[axis][bin_of(item.centroid[axis], low[axis], scale[axis])];
                b.box.grow(item.box);
                ++b.count;
            }
        }
        split best;
        for (int axis = 0; axis < 3; ++axis) {
            if (scale[axis] == 0)
                continue;
            const std::vector<bin>& bins = bins_[axis];
            // sweep from the right: right_cost_[s] = A_R N_R for the split before bin s
            aabb accumulated;
            std::size_t on_right = 0;
            for (std::size_t s = bin_count_ - 1; s > 0; --s) {
                accumulated.grow(bins[s].box);
                on_right += bins[s].count;
                right_box_[s] = accumulated;
                right_cost_[s] = half_area(accumulated) * real(on_right);
            }
            aabb left;
            std::size_t on_left = 0;
            for (std::size_t s = 1; s < bin_count_; ++s) {
                left.grow(bins[s - 1].box);
                on_left += bins[s - 1].count;
                if (on_left == 0 || on_left == end - begin)
                    continue;
                const real cost = half_area(left) * real(on_left) + right_cost_[s];
                if (best.axis < 0 || cost < best.cost) {
                    best.axis = axis;
                    best.bin = s;
                    best.cost = cost;
                    best.left = left;
                    best.right = right_box_[s];
                }
            }
        }
        return best;
    }

    binary_child leaf(std::size_t begin, std::size_t n, const aabb& box, real area)
    {
        sah_cost += double(options_.intersection_cost) * double(area) * double(n);
        binary_child c;
        c.box = box;
        c.index = std::uint32_t(begin);
        c.count = std::uint32_t(n);
        return c;
    }

    std::vector<build_item>& items_;
    const bvh_options& options_;
    int spare_threads_;
    std::size_t bin_count_;
    std::vector<bin> bins_[3];
    std::vector<real> right_cost_;
    std::vector<aabb> right_box_;
};

/// Turns the binary tree into 4-wide nodes (4-wide BVHs for single rays:
/// Wald, Benthin, Boulos, "Getting Rid of Packets", IEEE Symposium on
/// Interactive Ray Tracing 2008; Dammertz, Hanika, Keller, "Shallow Bounding
/// Volume Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays", EGSR
/// 2008): a node takes its two binary children, then repeatedly replaces its
/// inner child of largest surface area (the one most rays enter) by that
/// child's two children, until it has four. Nodes come out depth first.
class wide_collapser {
public:
    wide_collapser(const std::vector<binary_node>& binary, std::vector<bvh_node>& nodes, bvh_stats& stats)
        : binary_(binary), nodes_(nodes), stats_(stats)
    {
    }

    std::uint32_t collapse(const binary_child& root, int depth)
    {
        binary_child children[4];
        int used = 0;
        if (root.count != 0) { // the whole tree is one leaf
            children[used++] = root;
        } else {
            children[used++] = binary_[root.index].side[0];
            children[used++] = binary_[root.index].side[1];
        }
        while (used < 4) {
            int widest = -1;
            for (int c = 0; c < used; ++c)
                if (children[c].count == 0 &&
                    (widest < 0 || half_area(children[c].box) > half_area(children[widest].box)))
                    widest = c;
            if (widest < 0)
                break;
            const binary_node& opened = binary_[children[widest].index];
            children[widest] = opened.side[0];
            children[used++] = opened.side[1];
        }
        const std::uint32_t index = std::uint32_t(nodes_.size());
        nodes_.emplace_back();
        for (int c = 0; c < 4; ++c) {
            const aabb box = c < used ? children[c].box : aabb{};
            bvh_node& node = nodes_[index];
            for (int k = 0; k < 3; ++k) {
                node.bounds[2 * k][c] = box.lo[k];
                node.bounds[2 * k + 1][c] = box.hi[k];
            }
            node.child[c] = leaf_flag;
            node.count[c] = 0;
        }
        for (int c = 0; c < used; ++c) {
            if (children[c].count != 0) {
                nodes_[index].child[c] = leaf_flag | children[c].index;
                nodes_[index].count[c] = children[c].count;
                ++stats_.leaves;
                stats_.depth = std::max(stats_.depth, depth + 1);
            } else {
                const std::uint32_t below = collapse(children[c], depth + 1);
                nodes_[index].child[c] = below;
            }
        }
        return index;
    }

private:
    const std::vector<binary_node>& binary_;
    std::vector<bvh_node>& nodes_;
    bvh_stats& stats_;
};

#if RT_BVH_SSE
constexpr bool bvh_uses_sse = true;
#else
constexpr bool bvh_uses_sse = false;
#endif

/// The ray as the node test reads it (see the top of this file).
struct node_ray {
    real origin[3];
    real inv_dir[3];
    int near_row[3];  ///< per axis, the row of bvh_node::bounds met first: 2 k (lo) or 2 k + 1 (hi)
    int far_row[3];
#if RT_BVH_SSE
    __m128 origin4[3];   ///< the origin's k-th coordinate in all four lanes
    __m128 inv_dir4[3];  ///< 1/d_k in all four lanes
#endif
};

inline node_ray make_node_ray(const ray& r)
{
    const box_ray b = make_box_ray(r);
    node_ray n;
    for (int k = 0; k < 3; ++k) {
        n.origin[k] = b.origin[k];
        n.inv_dir[k] = b.inv_dir[k];
        n.near_row[k] = 2 * k + b.negative[k];
        n.far_row[k] = 2 * k + 1 - b.negative[k];
#if RT_BVH_SSE
        n.origin4[k] = _mm_set1_ps(float(b.origin[k]));
        n.inv_dir4[k] = _mm_set1_ps(float(b.inv_dir[k]));
#endif
    }
    return n;
}

/// The slab test of hit_box for the four children of `node` at once: bit c of
/// the result is set when child c is met in [tmin, tmax], and tnear[c] is then
/// where the ray enters it. One value at a time.
inline int intersect_children_scalar(const bvh_node& node, const node_ray& r, real tmin, real tmax, real tnear[4])
{
    int mask = 0;
    for (int c = 0; c < 4; ++c) {
        real t0 = tmin, t1 = tmax;
        for (int k = 0; k < 3; ++k) {
            const real t_near = (node.bounds[r.near_row[k]][c] - r.origin[k]) * r.inv_dir[k];
            const real t_far = (node.bounds[r.far_row[k]][c] - r.origin[k]) * r.inv_dir[k];
            t0 = t_near > t0 ? t_near : t0; // a NaN keeps the interval (see hit_box)
            t1 = t_far < t1 ? t_far : t1;
        }
        tnear[c] = t0;
        mask |= (t0 <= t1 * slab_far_factor ? 1 : 0) << c;
    }
    return mask;
}

#if RT_BVH_SSE
/// The same test with SSE, one child per lane. _mm_max_ps(a, b) is exactly
/// a > b ? a : b and _mm_min_ps(a, b) is a < b ? a : b, NaN included, so every
/// lane computes bit for bit what intersect_children_scalar computes.
inline int intersect_children_sse(const bvh_node& node, const node_ray& r, float tmin, float tmax, float tnear[4])
{
    // the three axes written out: the compiler keeps every value in a register
    const __m128 near_x = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.near_row[0]]), r.origin4[0]), r.inv_dir4[0]);
    const __m128 far_x = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.far_row[0]]), r.origin4[0]), r.inv_dir4[0]);
    const __m128 near_y = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.near_row[1]]), r.origin4[1]), r.inv_dir4[1]);
    const __m128 far_y = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.far_row[1]]), r.origin4[1]), r.inv_dir4[1]);
    const __m128 near_z = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.near_row[2]]), r.origin4[2]), r.inv_dir4[2]);
    const __m128 far_z = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.bounds[r.far_row[2]]), r.origin4[2]), r.inv_dir4[2]);
    const __m128 t0 = _mm_max_ps(near_z, _mm_max_ps(near_y, _mm_max_ps(near_x, _mm_set1_ps(tmin))));
    const __m128 t1 = _mm_min_ps(far_z, _mm_min_ps(far_y, _mm_min_ps(far_x, _mm_set1_ps(tmax))));
    _mm_storeu_ps(tnear, t0);
    return _mm_movemask_ps(_mm_cmple_ps(t0, _mm_mul_ps(t1, _mm_set1_ps(float(slab_far_factor)))));
}
#endif

inline int intersect_children(const bvh_node& node, const node_ray& r, real tmin, real tmax, real tnear[4])
{
#if RT_BVH_SSE
    return intersect_children_sse(node, r, tmin, tmax, tnear);
#else
    return intersect_children_scalar(node, r, tmin, tmax, tnear);
#endif
}

} // namespace detail

/// A BVH over packed primitives (see the top of this file). Built once; its
/// queries are const and safe to run from many threads at once.
class bvh {
public:
    bvh() = default;

    /// Builds the hierarchy; the primitives are reordered into leaf order.
    explicit bvh(std::vector<packed_primitive> prims, const bvh_options& options = {})
        : prims_(std::move(prims))
    {
        stats_.primitives = prims_.size();
        if (prims_.empty())
            return;
        if (prims_.size() >= std::size_t(leaf_flag))
            throw error("expected at most 2^31 - 1 primitives in one BVH, found " + std::to_string(prims_.size()));
        bvh_options used = options;
        used.max_depth = std::max(1, std::min(used.max_depth, max_depth));
        used.max_leaf_size = std::max<std::size_t>(1, used.max_leaf_size);

        std::vector<detail::build_item> items(prims_.size());
        aabb scene_box;
        for (std::size_t i = 0; i < prims_.size(); ++i) {
            items[i].box = packed_bounds(prims_[i]);
            items[i].centroid = items[i].box.center();
            items[i].index = std::uint32_t(i);
            scene_box.grow(items[i].box);
        }
        const int threads = used.threads > 0 ? used.threads : int(std::max(1u, std::thread::hardware_concurrency()));
        detail::binary_builder builder(items, used, threads - 1);
        builder.nodes.reserve(prims_.size());
        const detail::binary_child root = builder.build(0, items.size(), scene_box, 0);
        const std::vector<detail::binary_node>& binary = builder.nodes;
        const real root_area = detail::half_area(scene_box);
        stats_.sah_cost = root_area > 0 ? builder.sah_cost / double(root_area) : 0;
        stats_.binary_nodes = binary.size();

        nodes_.reserve(binary.size() / 2 + 1);
        detail::wide_collapser(binary, nodes_, stats_).collapse(root, 0);
        stats_.nodes = nodes_.size();

        std::vector<packed_primitive> ordered(prims_.size());
        for (std::size_t i = 0; i < items.size(); ++i)
            ordered[i] = prims_[items[i].index];
        prims_ = std::move(ordered);
    }

    /// The closest hit in [tmin, tmax] by replaces(), or false.
    bool closest(const ray& r, real tmin, real tmax, primitive_hit& best) const
    {
        return traverse<false, false>(r, tmin, tmax, best);
    }

    /// Whether anything is hit in [tmin, tmax]; stops at the first hit found.
    bool any(const ray& r, real tmin, real tmax) const
    {
        primitive_hit unused;
        return traverse<true, false>(r, tmin, tmax, unused);
    }

    /// closest() with the node test done one value at a time (the fallback
    /// where SSE is missing), for the tests to compare with closest().
    bool closest_scalar(const ray& r, real tmin, real tmax, primitive_hit& best) const
    {
        return traverse<false, true>(r, tmin, tmax, best);
    }

    const std::vector<bvh_node>& nodes() const { return nodes_; }
    const std::vector<packed_primitive>& primitives() const { return prims_; }
    const bvh_stats& stats() const { return stats_; }

    /// Whether the node test runs in SSE registers (x86-64 and rt::real = float).
    static constexpr bool uses_sse = detail::bvh_uses_sse;

    /// The deepest binary tree built; a 4-wide node pushes at most 3 children,
    /// so the traversal stack needs 3 entries per level.
    static constexpr int max_depth = 60;
    static constexpr int stack_size = 3 * max_depth + 4;

private:
    template <bool any_hit, bool scalar>
    bool traverse(const ray& r, real tmin, real tmax, primitive_hit& best) const
    {
        if (nodes_.empty())
            return false;
        const detail::node_ray nr = detail::make_node_ray(r);
        const watertight_ray wr = make_watertight_ray(r);
        struct entry {
            std::uint32_t child, count;
            real tnear;
        };
        entry stack[stack_size];
        int top = 0;
        bool found = false;
        real closest_t = tmax; // a hit must have t <= closest_t: tmax, then the closest hit so far
        std::uint32_t child = 0, count = 0; // the root
        for (;;) {
            if (!(child & leaf_flag)) {
                const bvh_node& node = nodes_[child];
                real tnear[4];
                const int mask = scalar ? detail::intersect_children_scalar(node, nr, tmin, closest_t, tnear)
                                        : detail::intersect_children(node, nr, tmin, closest_t, tnear);
                if (mask != 0) {
                    if constexpr (any_hit) {
                        // Any hit ends the search, so the order of the children
                        // cannot change the answer: enter the first one met and
                        // push the others unsorted. (Sorting them made shadow rays
                        // 1.6x slower on the bunny: bench/embree.cpp, docs/performance.md.)
                        int first = -1;
                        for (int c = 0; c < 4; ++c)
                            if (mask & (1 << c)) {
                                if (first < 0)
                                    first = c;
                                else
                                    stack[top++] = entry{node.child[c], node.count[c], tnear[c]};
                            }
                        child = node.child[first];
                        count = node.count[first];
                        continue;
                    }
                    entry hits[4];
                    int n = 0;
                    for (int c = 0; c < 4; ++c)
                        if (mask & (1 << c))
                            hits[n++] = entry{node.child[c], node.count[c], tnear[c]};
                    for (int i = 1; i < n && !any_hit; ++i) // any hit: no order needed
                        for (int j = i; j > 0 && hits[j].tnear < hits[j - 1].tnear; --j) {
                            const entry swap = hits[j];
                            hits[j] = hits[j - 1];
                            hits[j - 1] = swap;
                        }
                    for (int i = n - 1; i > 0; --i)
                        stack[top++] = hits[i];
                    child = hits[0].child;
                    count = hits[0].count;
                    continue;
                }
            } else {
                for (std::uint32_t i = child & ~leaf_flag, last = i + count; i < last; ++i) {
                    primitive_hit h;
                    if (intersect_packed(prims_[i], r, wr, tmin, closest_t, h) && (!found || replaces(h, best))) {
                        best = h;
                        if (any_hit)
                            return true;
                        found = true;
                        closest_t = h.t;
                    }
                }
            }
            // the next entry on the stack that can still hold a hit at t <= closest_t
            const real cut = closest_t * slab_far_factor;
            for (;;) {
                if (top == 0)
                    return found;
                const entry& e = stack[--top];
                if (e.tnear <= cut) {
                    child = e.child;
                    count = e.count;
                    break;
                }
            }
        }
    }

    std::vector<packed_primitive> prims_;
    std::vector<bvh_node> nodes_;
    bvh_stats stats_;
};

} // namespace rt

#undef RT_BVH_SSE
