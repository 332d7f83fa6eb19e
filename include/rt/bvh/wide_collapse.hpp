// bvh/wide_collapse.hpp - the binary tree made wide (layout.hpp's nodes, bvh_width children).
// (No #pragma once: a unit may compile this file once per width, bvh/dispatch.hpp;
// the guard after the section opens keeps one copy of each.)

#include <algorithm>
#include <cstdint>
#include <vector>

#include "../core/aabb.hpp"
#include "build_store.hpp"
#include "build_options.hpp"
#include "layout.hpp"
#include "parallel_fill.hpp"

#include "abi_begin.hpp" // RT_BVH_ABI, until simd_end.hpp
#if RT_BVH_AVX512 ? !defined(RT_BVH_WIDE_COLLAPSE_W8X) : RT_BVH_AVX2 ? !defined(RT_BVH_WIDE_COLLAPSE_W8) : !defined(RT_BVH_WIDE_COLLAPSE_W4)
#if RT_BVH_AVX512
#define RT_BVH_WIDE_COLLAPSE_W8X
#elif RT_BVH_AVX2
#define RT_BVH_WIDE_COLLAPSE_W8
#else
#define RT_BVH_WIDE_COLLAPSE_W4
#endif

namespace rt {
namespace detail {
RT_BVH_ABI_INLINE namespace RT_BVH_ABI { // this width's fast path (bvh/abi_begin.hpp)

/// Turns the binary tree into bvh_width-wide nodes (wide BVHs for single rays:
/// Wald, Benthin, Boulos, "Getting Rid of Packets", IEEE Symposium on
/// Interactive Ray Tracing 2008; Dammertz, Hanika, Keller, "Shallow Bounding
/// Volume Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays", EGSR
/// 2008): a node takes its two binary children, then repeatedly replaces its
/// inner child of largest surface area (the one most rays enter) by that
/// child's two children, until it has bvh_width. Nodes come out depth first.
class wide_collapser {
public:
    wide_collapser(const binary_node_store& binary, large_array<bvh_node>& nodes, bvh_stats& stats)
        : binary_(binary), nodes_(nodes), stats_(stats)
    {
    }

    std::uint32_t collapse(const binary_child& root, int depth)
    {
        binary_child children[bvh_width];
        int used = 0;
        if (root.count != 0) { // the whole tree is one leaf
            children[used++] = root;
        } else {
            children[used++] = binary_[root.index].side[0];
            children[used++] = binary_[root.index].side[1];
        }
        while (used < bvh_width) {
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
        for (int c = 0; c < bvh_width; ++c) {
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
    const binary_node_store& binary_;
    large_array<bvh_node>& nodes_;
    bvh_stats& stats_;
};

} // namespace RT_BVH_ABI
} // namespace detail
} // namespace rt

#endif // RT_BVH_WIDE_COLLAPSE_W8X / _W8 / _W4

#include "simd_end.hpp"
