// bvh/build_options.hpp - what a BVH build takes and makes: its options, its
// statistics, and the binary tree the builders write before it is made wide.
//
//     rt::bvh_options options;
//     options.threads = 1;          // the tree is the same for any count
//     options.spatial_budget = 0;   // no spatial splits
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "../core/aabb.hpp"
#include "../core/config.hpp"
#include "../core/vec.hpp"

namespace rt {


/// How a BVH is built (binned_builder.hpp, spatial_split.hpp). The defaults were chosen by
/// measuring primary rays on the Stanford bunny (docs/stages/04-triangle.md).
struct bvh_options {
    int bins = 16;                    ///< SAH slices per axis, at most (a node of n primitives: 4 + n / 20)
    std::size_t max_leaf_size = 8;    ///< a node with more primitives is always split
    real traversal_cost = 1;          ///< C_trav: one node visit
    real intersection_cost = 1;       ///< C_isect: one leaf test of up to primitives_per_test primitives
    std::size_t primitives_per_test = 4; ///< the SAH counts a leaf's primitives in blocks of this many
    int max_depth = 60;               ///< a node this deep in the binary tree becomes a leaf
    int threads = 0;                  ///< threads for the build; 0: one per core, at most 4 per core (the tree is the same)
    /// Spatial splits (see binary_builder::build_spatial): at most this many
    /// extra references, as a fraction of the primitives (taken in [0, 4]:
    /// the build reserves room for them); 0 turns them off.
    real spatial_budget = real(0.3);
    /// A node tries spatial splits when its best object split's children
    /// overlap by more than this fraction of the root's surface area. Stich
    /// et al. use 1e-5; 3e-3 keeps Sponza's gain at about half the extra
    /// build time (docs/performance.md, experiment 6).
    real spatial_overlap = real(3e-3);
    /// Slices per axis of the spatial split search (find_spatial_split): a
    /// reference is clipped against each plane it crosses, so this count sets
    /// the search's cost; 8 traces as fast as 16 and builds faster (the
    /// figure: docs/architecture.md, "Figures behind the comments").
    int spatial_bins = 8;
};

/// What a build produced.
struct bvh_stats {
    std::size_t primitives = 0;
    std::size_t references = 0;   ///< primitives plus the extra pieces made by spatial splits
    std::size_t spatial_splits = 0; ///< binary nodes split by a plane that cuts primitives
    std::size_t nodes = 0;        ///< wide nodes (bvh_width children each)
    std::size_t leaves = 0;
    std::size_t binary_nodes = 0; ///< inner nodes of the binary tree before collapsing
    int depth = 0;                ///< the deepest leaf: the root's children are at depth 1
    double sah_cost = 0;          ///< the binary tree's SAH cost, in units of one primitive test
};

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

/// The leaf tests that n primitives cost: ceil(n / per_test) (the SIMD leaf
/// test handles a block of four triangles at the price of about one; Embree's
/// SAH counts its triangle4 blocks the same way).
inline real leaf_tests(std::size_t n, std::size_t per_test)
{
    const std::size_t per = std::max<std::size_t>(1, per_test);
    return real((n + per - 1) / per);
}

/// The bin of a coordinate (a centroid; a box's side in spatial_split.hpp): slot = (c - low) scale, truncated, held in
/// [0, count - 1] (a NaN goes to bin 0). The SSE form computes the same value
/// from the same stored centroid (a difference of two products would let the
/// compiler fuse them, and the binning and the partition could then disagree).
inline std::size_t bin_of(real centroid, real low, real scale, std::size_t count)
{
    real slot = (centroid - low) * scale;
    slot = slot > 0 ? slot : real(0); // (selects, not branches: a NaN goes to 0)
    slot = slot < real(count - 1) ? slot : real(count - 1);
    return std::size_t(slot);
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

} // namespace detail

} // namespace rt
