// bvh/bvh.hpp - the fast path: a bounding volume hierarchy over packed
// primitives, the engine behind rt::accelerator (accelerator.hpp).
//
// The course's group is a list searched from start to end (hit_list.hpp,
// stage 04); with n shapes every ray pays n tests. A BVH puts the shapes in
// nested boxes, so a ray that misses a box skips all of its shapes: about
// log n box tests instead of n shape tests. The list and the BVH return the
// same hits (replaces(): a smaller t wins, at an equal t the later primitive).
//
// The folder, one concept per header, in the order a build and a ray use them:
//   abi_begin.hpp       which fast path this unit compiles, and its inline namespace
//   simd_begin.hpp      that, with the intrinsics it allows (opens a SIMD section)
//   simd_end.hpp        the section closed: no fast-path macro reaches an includer
//   packed.hpp          a primitive as traversal reads it; the flat list
//   layout.hpp          wide nodes (8 children with AVX2, else 4), leaf blocks
//   box_test.hpp        the robust slab test (Williams et al. 2005, Ize 2013)
//   build_options.hpp   bvh_options, bvh_stats, the binary tree
//   builtins.hpp        the compiler's bit scan, prefetch and CPU test, one name each
//   build_store.hpp     its nodes and references, written by all the build's threads
//   sah_bins.hpp        the SAH's bins and sweep, the partition (SSE / scalar)
//   spatial_split.hpp   planes that cut large triangles (Stich et al. 2009)
//   build_tasks.hpp     the build's threads: subtrees offered to idle ones
//   parallel_fill.hpp   large arrays written on the build's threads
//   binned_builder.hpp  the binned SAH build (Wald 2007), on threads
//   wide_collapse.hpp   the binary tree made wide
//   node_test.hpp       a ray against a node's boxes, all at once
//   descend.hpp         the child a ray enters next, the others pushed
//   leaf_test.hpp       a ray against a block's four triangles (SSE / scalar)
//   hit_fill.hpp        a hit's record from its block (SSE), for rt::accelerator
//   bvh.hpp             this file: build, then closest_hit() and any_hit()
//   dispatch.hpp        the 8-wide path again, for AVX2 CPUs, in a unit built without AVX2
//   accelerator.hpp     rt::accelerator: a scene's shapes behind the BVH or a flat list
//   accelerator_fwd.hpp rt::accelerator declared, for a header that only names it
// What each choice bought, measured, is in docs/performance.md (experiment 6).
//
//     const std::vector<rt::packed_primitive> prims = {rt::pack_triangle(a, b, c, 0)};
//     const rt::bvh tree(prims);
//     rt::primitive_hit hit;
//     if (tree.closest_hit(ray, 0, rt::infinity, hit)) { /* hit.t, hit.id */ }
//     const bool blocked = tree.any_hit(shadow_ray, 0, 1);
//
// Traversal keeps a fixed-size stack of children with their entry distances
// (no allocation per ray) and skips an entry whose distance is beyond the
// closest hit found meanwhile; any_hit() returns at the first hit and pushes
// children unsorted (their order cannot change its answer). The next child is
// chosen by one jump on the mask of children met, whose cases know their
// children at compile time (descend.hpp): on coherent rays the jump is
// predicted and the next node loads before the box test has finished.
// (No #pragma once: a unit may compile this file once per width, bvh/dispatch.hpp;
// the guard after the section opens keeps one copy of each.)

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "../core/aabb.hpp"
#include "../core/error.hpp"
#include "../core/ray.hpp"
#include "../intersection/watertight.hpp"
#include "binned_builder.hpp"
#include "build_tasks.hpp"
#include "build_options.hpp"
#include "build_store.hpp"
#include "builtins.hpp"
#include "descend.hpp"
#include "layout.hpp"
#include "leaf_test.hpp"
#include "node_test.hpp"
#include "packed.hpp"
#include "parallel_fill.hpp"
#include "wide_collapse.hpp"

#include "simd_begin.hpp" // RT_BVH_ABI, RT_BVH_INLINE, until simd_end.hpp
#if RT_BVH_AVX512 ? !defined(RT_BVH_BVH_W8X) : RT_BVH_AVX2 ? !defined(RT_BVH_BVH_W8) : !defined(RT_BVH_BVH_W4)
#if RT_BVH_AVX512
#define RT_BVH_BVH_W8X
#elif RT_BVH_AVX2
#define RT_BVH_BVH_W8
#else
#define RT_BVH_BVH_W4
#endif

namespace rt {
RT_BVH_ABI_INLINE namespace RT_BVH_ABI { // this width's fast path (bvh/abi_begin.hpp)

/// A BVH over packed primitives (see the top of this file). Built once; its
/// queries are const and safe to run from many threads at once.
class bvh {
public:
    bvh() = default;

    /// Builds the hierarchy over prims[0, count); the tree keeps its own copy
    /// of them, four by four in leaf order (blocks()), not `prims`.
    bvh(const packed_primitive* prims, std::size_t count, const bvh_options& options = {})
    {
        stats_.primitives = count;
        if (count == 0)
            return;
        if (count >= std::size_t(detail::leaf_flag))
            throw error("expected at most 2^31 - 1 primitives in one BVH, found " + std::to_string(count));
        check(options);
        bvh_options used = options;
        used.max_depth = std::max(1, std::min(used.max_depth, max_depth));
        used.max_leaf_size = std::max<std::size_t>(1, used.max_leaf_size);
        const int threads = detail::binary_builder::threads_for(count, used.threads);

        // the references: the primitives' boxes first, then (spatial splits)
        // pieces of them, at most `budget` more (build_store.hpp); the
        // fraction held in [0, 4], a NaN taken as 0
        const real asked = used.spatial_budget;
        const real fraction = asked > real(4) ? real(4) : asked > 0 ? asked : real(0);
        const std::size_t budget = std::size_t(double(fraction) * double(count));
        detail::item_pool items(count + budget);
        detail::build_item* const first = items.data();
        detail::side_bounds all; // the items' box, centroids and widest extents, for build_spatial
        std::mutex all_mutex;    // and has_spheres_
        detail::fill_in_parallel(count, threads, [&](std::size_t begin, std::size_t end) {
            detail::side_bounds part;
            bool spheres = false;
            for (std::size_t i = begin; i < end; ++i) {
                const aabb box = packed_bounds(prims[i]);
                const detail::build_item& item = *::new (static_cast<void*>(first + i))
                    detail::build_item{box, box.center(), std::uint32_t(i)};
                part.add(item);
                spheres = spheres || (prims[i].id & sphere_flag) != 0;
            }
            const std::lock_guard<std::mutex> lock(all_mutex);
            all.merge(part);
            has_spheres_ = has_spheres_ || spheres;
        });
        const aabb& scene_box = all.box;
        detail::build_tasks tasks;
        detail::binary_node_store binary;
        detail::binary_builder builder(items, binary, used, threads > 1 ? &tasks : nullptr, prims);
        detail::binary_child root;
        tasks.run(threads, [&] {
            if (budget > 0)
                root = builder.build_spatial(count, detail::half_area(scene_box), budget, all);
            else
                root = builder.build(0, count, scene_box, 0);
        });
        stats_.references = count + builder.pieces;
        stats_.spatial_splits = builder.spatial_splits;
        const real root_area = detail::half_area(scene_box);
        stats_.sah_cost = root_area > 0 ? builder.sah_cost / double(root_area) : 0;
        stats_.binary_nodes = builder.node_count;

        nodes_.reserve(builder.node_count / 2 + 1);
        detail::wide_collapser(binary, nodes_, stats_).collapse(root, 0);
        stats_.nodes = nodes_.size();
        pack_blocks(prims, items.data(), threads);
    }

    /// The same, over a vector.
    explicit bvh(const std::vector<packed_primitive>& prims, const bvh_options& options = {})
        : bvh(prims.data(), prims.size(), options)
    {
    }

    /// The closest hit in [tmin, tmax] by replaces(), or false.
    bool closest_hit(const ray& r, real tmin, real tmax, primitive_hit& best) const
    {
        return traverse<false, false>(r, tmin, tmax, best);
    }

    /// Whether anything is hit in [tmin, tmax]; stops at the first hit found.
    bool any_hit(const ray& r, real tmin, real tmax) const
    {
        primitive_hit unused;
        return traverse<true, false>(r, tmin, tmax, unused);
    }

    /// closest_hit() with the node and leaf tests done one value at a time (the
    /// fallback where SSE is missing), for the tests to compare with closest_hit().
    bool closest_hit_scalar(const ray& r, real tmin, real tmax, primitive_hit& best) const
    {
        return traverse<false, true>(r, tmin, tmax, best);
    }

    /// any_hit() one value at a time, as closest_hit_scalar.
    bool any_hit_scalar(const ray& r, real tmin, real tmax) const
    {
        primitive_hit unused;
        return traverse<true, true>(r, tmin, tmax, unused);
    }

    const detail::large_array<detail::bvh_node>& nodes() const { return nodes_; }
    /// The leaves' primitives as blocks of four, in the order the nodes meet
    /// the leaves (a leaf's reference in bvh_node::child is leaf_flag | its
    /// first block); a primitive that spatial splits cut appears once per leaf
    /// that holds a piece of it.
    const detail::large_array<detail::triangle_block>& blocks() const
    {
        return blocks_;
    }
    const bvh_stats& stats() const { return stats_; }

    /// Whether the node test runs in SSE registers (x86-64 and rt::real = float).
    static constexpr bool uses_sse = detail::bvh_uses_sse;

    /// The deepest binary tree built; a node pushes at most bvh_width - 1
    /// children, so the traversal stack needs that many entries per level.
    static constexpr int max_depth = 60;
    static constexpr int stack_size = (bvh_width - 1) * max_depth + bvh_width;

private:
    /// The SAH costs and the overlap threshold are refused when they are not
    /// finite numbers of the right sign: a NaN would not break the tree but
    /// would silently build a useless one (every node split to the bottom).
    static void check(const bvh_options& o)
    {
        auto is = [](real x, bool positive) { return std::isfinite(x) && (positive ? x > 0 : x >= 0); };
        if (!is(o.traversal_cost, false) || !is(o.intersection_cost, true) || !is(o.spatial_overlap, false))
            throw error("bvh_options: expected traversal_cost >= 0, intersection_cost > 0 and spatial_overlap >= 0, "
                        "all finite, found " + std::to_string(double(o.traversal_cost)) + ", " +
                        std::to_string(double(o.intersection_cost)) + " and " +
                        std::to_string(double(o.spatial_overlap)));
    }

    /// Each leaf's primitives as blocks of four (layout.hpp), in the order the
    /// nodes meet the leaves (depth first): first where each leaf's blocks
    /// go, one pass over the nodes, then the blocks themselves on threads
    /// (parallel_fill.hpp). A leaf's reference becomes its first block; count
    /// stays its number of primitives.
    void pack_blocks(const packed_primitive* prims, const detail::build_item* items, int threads)
    {
        struct leaf_blocks {
            std::uint32_t first_item, count, first_block;
        };
        std::vector<leaf_blocks> leaves;
        leaves.reserve(stats_.leaves);
        std::size_t block_count = 0;
        for (detail::bvh_node& node : nodes_)
            for (int c = 0; c < bvh_width; ++c) {
                if (!(node.child[c] & detail::leaf_flag) || node.count[c] == 0)
                    continue;
                leaves.push_back(leaf_blocks{node.child[c] & ~detail::leaf_flag, node.count[c], std::uint32_t(block_count)});
                node.child[c] = detail::leaf_flag | std::uint32_t(block_count);
                block_count += (node.count[c] + 3) / 4;
            }
        blocks_.resize(block_count); // not written yet: every block is assigned below
        detail::fill_in_parallel(
            leaves.size(), threads,
            [&](std::size_t begin, std::size_t end) {
                for (std::size_t l = begin; l < end; ++l) {
                    // the primitives are read in leaf order, scattered over
                    // prims: ask for those of a leaf 8 ahead, so they are in
                    // cache when its turn comes
                    if (l + 8 < end)
                        for (std::uint32_t k = 0; k < leaves[l + 8].count && k < 8; ++k)
                            detail::prefetch(&prims[items[leaves[l + 8].first_item + k].index]);
                    const leaf_blocks& leaf = leaves[l];
                    for (std::uint32_t done = 0; done < leaf.count; done += 4) {
                        const packed_primitive* lanes[4] = {};
                        const std::uint32_t n = std::min<std::uint32_t>(4, leaf.count - done);
                        for (std::uint32_t lane = 0; lane < n; ++lane)
                            lanes[lane] = &prims[items[leaf.first_item + done + lane].index];
                        blocks_[leaf.first_block + done / 4] = detail::RT_BVH_ABI::pack_triangle_block(lanes, n); // (layout.hpp)
                    }
                }
            },
            1024);
    }

    // In bvh/dispatch.hpp's section the walk is inlined into closest_hit and
    // any_hit, which a dispatching program calls: one call per ray, as where
    // the walk is compiled for the unit's own target (any_hit had been a call
    // to a call: the Cornell box's shadow rays ran at 0.94 of a -march=native build)
    template <bool stop_at_first, bool scalar>
#if defined(RT_BVH_AVX2_SECTION)
    RT_BVH_INLINE
#endif
    bool traverse(const ray& r, real tmin, real tmax, primitive_hit& best) const
    {
        if (nodes_.empty())
            return false;
        const detail::node_ray nr = detail::make_node_ray(r);
        const watertight_ray wr = make_watertight_ray(r);
        const detail::leaf_ray lr = detail::make_leaf_ray(wr);
        detail::traversal_stack<stack_size> stack;
        int top = 0;
        bool found = false;
        real closest_t = tmax; // a hit must have t <= closest_t: tmax, then the closest hit so far
        std::uint32_t child = 0, count = 0; // the root
        for (;;) {
            if (!(child & detail::leaf_flag)) {
                const detail::bvh_node& node = nodes_[child];
                alignas(32) real tnear[bvh_width];
                const int mask = scalar ? detail::intersect_children_scalar(node, nr, tmin, closest_t, tnear)
                                        : detail::intersect_children(node, nr, tmin, closest_t, tnear);
                if (mask != 0) { // one jump on the mask (descend.hpp)
                    detail::descend<stop_at_first>(mask, node, tnear, stack, top, child, count);
                    continue;
                }
            } else {
                // a leaf: its blocks of four, each tested at once
                // (leaf_test.hpp); a block's hits are taken by replaces(),
                // so the closest hit does not depend on the order of the lanes
                const detail::triangle_block* block = blocks_.data() + (child & ~detail::leaf_flag);
                for (std::uint32_t done = 0; done < count; done += 4, ++block) {
                    detail::block_hits hits;
                    int mask = scalar ? detail::intersect_block_scalar(*block, wr, tmin, closest_t, hits)
                                      : detail::intersect_block<!stop_at_first>(*block, lr, wr, tmin, closest_t, hits);
                    if (mask != 0 && stop_at_first)
                        return true;
                    if (mask != 0) {
                        // the block's closest lane, then one decision against
                        // the closest hit so far; best written field by
                        // field: a primitive_hit built and copied whole was
                        // stored in parts and reloaded at once, a
                        // store-forwarding stall
                        const int lane = detail::closest_lane(mask, hits, *block);
                        const std::uint32_t id = block->id[lane];
                        if (!found || replaces(hits.t[lane], id, best)) {
                            best.t = hits.t[lane];
                            best.b0 = hits.b0[lane];
                            best.b1 = hits.b1[lane];
                            best.b2 = hits.b2[lane];
                            best.id = id;
                            best.corners = &block->v[0][lane];
                            best.stride = 4;
                            best.normal = &block->n[lane];
                            found = true;
                            closest_t = hits.t[lane];
                        }
                    }
                    if (!has_spheres_) // most scenes: no need to look at the ids
                        continue;
                    for (int spheres = detail::sphere_lanes(*block), lane = 0; spheres != 0; ++lane, spheres >>= 1) {
                        if (!(spheres & 1))
                            continue;
                        packed_primitive p{{0, 0, 0, 0, 0, 0, 0, 0, 0}, block->id[lane]};
                        for (int j = 0; j < 4; ++j)
                            p.v[j] = block->v[j][lane];
                        primitive_hit h;
                        if (detail::intersect_packed(p, r, wr, tmin, closest_t, h) && (!found || replaces(h, best))) {
                            best = h;
                            if (stop_at_first)
                                return true;
                            found = true;
                            closest_t = h.t;
                        }
                    }
                }
            }
            // the next entry on the stack that can still hold a hit at t <= closest_t
            const real cut = closest_t * slab_robust_far_factor;
            for (;;) {
                if (top == 0)
                    return found;
                --top;
                if (stack.t[top] <= cut) {
                    child = stack.child[top];
                    count = stack.count[top];
                    break;
                }
            }
        }
    }

    detail::large_array<detail::bvh_node> nodes_;  // large_array: huge pages (parallel_fill.hpp)
    detail::large_array<detail::triangle_block> blocks_;
    bool has_spheres_ = false;
    bvh_stats stats_;
};

} // namespace RT_BVH_ABI
} // namespace rt

#endif // RT_BVH_BVH_W8X / _W8 / _W4

#include "simd_end.hpp"
