// bvh/build_store.hpp - where the build's threads write: the binary tree's
// nodes and the references of its leaves, each in one store that all the
// builders (binned_builder.hpp) share, so a subtree built on another thread is
// in place when it joins: nothing is copied at a join, and no page is faulted
// in twice (docs/performance.md, experiment 6).
//
//  - binary_node_store: a builder takes runs of `run` consecutive indices,
//    whose nodes are consecutive in memory, and constructs its nodes there.
//    The store is segments of doubling size, segment s holding 2^s runs: it
//    grows without a bound known in advance, nothing written moves, and an
//    index finds its segment with one bit scan.
//  - item_pool: one array of a capacity known in advance, the primitives
//    and the spatial splits' budget, uninitialised: the primitives' items
//    are written to [0, n), and a node with spatial splits works in a range
//    with room for its budget after it (binary_builder::spatial_node).
// Where a node lies depends on which thread took its run first; the wide
// collapse follows the tree from its root and the leaf blocks follow the
// leaves, so the tree and the blocks do not.
//
//     rt::detail::binary_node_store nodes;
//     const std::uint32_t first = nodes.take_run(); // on any thread: `run` indices of its own
//     ::new (&nodes[first]) rt::detail::binary_node; // its storage is not initialised
//     rt::detail::item_pool items(capacity);         // items.data()[0, capacity), not initialised
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <mutex>

#include "../core/error.hpp"
#include "build_options.hpp"
#include "builtins.hpp"
#include "parallel_fill.hpp"

namespace rt {
namespace detail {

/// The binary tree's nodes (see the top of this file).
class binary_node_store {
public:
    /// Indices a builder takes at a time (16 KB of nodes).
    static constexpr std::uint32_t run = 256;

    binary_node_store() = default;
    binary_node_store(const binary_node_store&) = delete;
    binary_node_store& operator=(const binary_node_store&) = delete;
    ~binary_node_store()
    {
        for (int s = 0; s < segments; ++s)
            if (segment_[s] != nullptr)
                allocator().deallocate(segment_[s], runs_in(s) * run);
    }

    /// The first of `run` consecutive indices that no other call returns (any thread).
    std::uint32_t take_run()
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        const std::uint32_t r = runs_;
        const int s = segment_of(r);
        if (s >= segments)
            throw error("expected at most 2^31 nodes in a binary tree; split the scene");
        if (segment_[s] == nullptr) // the first run of its segment
            segment_[s] = allocator().allocate(runs_in(s) * run);
        ++runs_;
        return r * run;
    }

    /// Node i; its storage holds a node once the builder that took i made one there.
    binary_node& operator[](std::uint32_t i) { return at(i); }
    const binary_node& operator[](std::uint32_t i) const { return at(i); }

private:
    static constexpr int segments = 23; ///< 2^23 - 1 runs: 2^31 nodes, less one run

    static large_array_allocator<binary_node> allocator() { return {}; }
    static std::size_t runs_in(int s) { return std::size_t(1) << s; }

    /// The segment of run r: s with 2^s <= r + 1 < 2^(s + 1); runs 2^s - 1 on are in it.
    static int segment_of(std::uint32_t r)
    {
        const std::uint32_t x = r + 1;
        return highest_bit(x);
    }

    binary_node& at(std::uint32_t i) const
    {
        const int s = segment_of(i / run);
        return segment_[s][i - (runs_in(s) - 1) * run];
    }

    std::mutex mutex_;                      ///< guards runs_ and the making of segments
    binary_node* segment_[segments] = {};   ///< written once each, under mutex_
    std::uint32_t runs_ = 0;
};

/// The references of one build (see the top of this file): storage for
/// `capacity` build_items, not initialised (a range holds items once written).
class item_pool {
public:
    explicit item_pool(std::size_t capacity)
        : data_(allocator().allocate(std::max<std::size_t>(capacity, 1))), capacity_(capacity)
    {
    }
    item_pool(const item_pool&) = delete;
    item_pool& operator=(const item_pool&) = delete;
    ~item_pool() { allocator().deallocate(data_, std::max<std::size_t>(capacity_, 1)); }

    build_item* data() { return data_; }
    const build_item* data() const { return data_; }

private:
    static large_array_allocator<build_item> allocator() { return {}; }
    build_item* data_;
    std::size_t capacity_;
};

} // namespace detail
} // namespace rt
