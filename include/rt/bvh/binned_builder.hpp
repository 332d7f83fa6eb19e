// bvh/binned_builder.hpp - the binned SAH build of a binary tree.
//
// Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies", IEEE
// Symposium on Interactive Ray Tracing 2007, sec. 3: top down; each node's
// primitives are sorted into `bins` equal slices of their centroids' extent on
// each axis, and the node is split at the slice boundary of least surface area
// heuristic cost (MacDonald, Booth, The Visual Computer 6(3), 1990):
//     C = C_trav + C_isect (A_L B(N_L) + A_R B(N_R)) / A,
// A the surface areas of the boxes, N the primitive counts and B(N) =
// ceil(N / 4) the leaf tests they cost (leaf_tests: a leaf is tested a block
// of four at a time). A node becomes a leaf when that is cheaper than any split
// and it holds at most max_leaf_size primitives, or at max_depth. At the top
// of the tree, build_spatial also tries planes that cut primitives
// (spatial_split.hpp). wide_collapse.hpp then makes the tree bvh_width-wide.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "../core/aabb.hpp"
#include "../core/config.hpp"
#include "../system/parallel.hpp"
#include "../core/vec.hpp"
#include "build_store.hpp"
#include "build_options.hpp"
#include "build_tasks.hpp"
#include "packed.hpp"
#include "sah_bins.hpp"
#include "spatial_split.hpp"

namespace rt {
namespace detail {

/// The binned SAH build of a binary tree (see the top of this file).
///
/// Speed: one pass over a node's primitives bins them on all three axes at
/// once (sah_bins.hpp), its two halves on two threads for a node of 65,536 or
/// more; a node of 4,096 or more offers its right child to an idle thread
/// (build_tasks.hpp; bvh_options::threads). Nodes and references go to shared
/// stores (build_store.hpp); the tree is the same whatever the number of threads.
class binary_builder {
public:
    /// A builder over `items`; `tasks` (nullptr: one thread) shares its large
    /// nodes' subtrees among threads. Call build() or build_spatial()
    /// inside tasks->run().
    binary_builder(item_pool& items, binary_node_store& nodes, const bvh_options& options, build_tasks* tasks,
                   const packed_primitive* prims = nullptr)
        : items_(items), nodes_(nodes), options_(options), tasks_(tasks), prims_(prims),
          bin_count_(std::size_t(std::max(2, std::min(options.bins, 256)))),
          slice_count_(std::size_t(std::max(2, std::min(options.spatial_bins, 256)))),
          bins_(bin_count_, options.primitives_per_test) {}

    /// Below this many primitives a subtree is not worth a thread.
    static constexpr std::size_t parallel_threshold = 4096;

    /// The threads a build over n primitives uses: one for a tree too small to
    /// fork, else thread_count(asked), at most four a hardware thread (more
    /// would only take turns on the same cores, and a request of a million
    /// would try to start a million).
    static int threads_for(std::size_t n, int asked)
    {
        return n < parallel_threshold ? 1 : std::min(thread_count(asked), 4 * thread_count(0));
    }

    std::size_t node_count = 0; ///< the nodes this builder and the builders it joined made
    double sah_cost = 0; ///< the sum of C A over the subtree, before dividing by the root's area
    std::size_t spatial_splits = 0;

    std::size_t pieces = 0; ///< references added by spatial splits, beyond the primitives

    /// The tree with spatial splits at its top (Stich, Friedrich, Dietrich,
    /// "Spatial Splits in Bounding Volume Hierarchies", HPG 2009) over items
    /// [0, n), with room for `budget` more references after them; `bounds`
    /// are the items' (side_bounds). A node whose best object split leaves
    /// two children that overlap by more than spatial_overlap of the root's
    /// area also bins its references between planes that may cut them
    /// (find_spatial_split); if that costs less by the SAH, a reference that
    /// straddles the plane goes to both children, each with the box of its
    /// part (cut_references). The pieces are references to the same
    /// primitive, so a ray gets the same hit whichever it meets. A node where
    /// the overlap is small, or whose subtree is small, is handed to build().
    binary_child build_spatial(std::size_t n, real root_area, std::size_t budget, const side_bounds& bounds)
    {
        return spatial_node(0, n, budget, 0, root_area, bounds);
    }

    /// Builds the subtree of items [begin, end) inside `box`; returns it as a
    /// child. `known` and `known_centroids`, when given, are this node's best
    /// split and centroid box, already found by build_spatial.
    binary_child build(std::size_t begin, std::size_t end, const aabb& box, int depth, const split* known = nullptr,
                       const aabb* known_centroids = nullptr)
    {
        const std::size_t n = end - begin;
        const real area = half_area(box);
        if (n <= 1 || depth >= options_.max_depth)
            return leaf(begin, n, box, area);
        // One leaf test: no split costs less when C_trav >= C_isect (split
        // cost >= C_trav, leaf cost C_isect), so the bins are not filled
        if (n <= options_.primitives_per_test && n <= options_.max_leaf_size && area > 0 &&
            options_.traversal_cost >= options_.intersection_cost)
            return leaf(begin, n, box, area);

        aabb centroids;
        if (known_centroids != nullptr)
            centroids = *known_centroids;
        else
            for (std::size_t i = begin; i < end; ++i)
                centroids.grow(items_.data()[i].centroid);

        aabb left_box, right_box, left_centroids, right_centroids;
        std::size_t middle = begin;
        const split best = known != nullptr ? *known : find_split(items_.data() + begin, n, centroids);
        if (best.axis < 0) {
            // every centroid is the same point: no plane separates them
            if (n <= options_.max_leaf_size)
                return leaf(begin, n, box, area);
            middle = begin + n / 2;
            left_centroids = right_centroids = centroids;
            for (std::size_t i = begin; i < middle; ++i)
                left_box.grow(items_.data()[i].box);
            for (std::size_t i = middle; i < end; ++i)
                right_box.grow(items_.data()[i].box);
        } else {
            const real split_cost =
                area > 0 ? options_.traversal_cost + options_.intersection_cost * best.cost / area : real(0);
            const real leaf_cost = options_.intersection_cost * tests(n);
            if (n <= options_.max_leaf_size && leaf_cost <= split_cost)
                return leaf(begin, n, box, area);
            side_bounds l, r;
            middle = begin + partition_items(items_.data() + begin, n, best, l, r);
            left_box = l.box;
            right_box = r.box;
            left_centroids = l.centroids;
            right_centroids = r.centroids;
        }

        // the right half sorts its own range of items_ in place
        return inner_node(
            box, area, n, [&] { return build(begin, middle, left_box, depth + 1, nullptr, &left_centroids); },
            [&](binary_builder& b) { return b.build(middle, end, right_box, depth + 1, nullptr, &right_centroids); });
    }

private:
    /// build_spatial over items [begin, end), with room for `budget` more
    /// references at [end, end + budget); `bounds` are the items'.
    binary_child spatial_node(std::size_t begin, std::size_t end, std::size_t budget, int depth, real root_area,
                              const side_bounds& bounds)
    {
        build_item* const refs = items_.data() + begin;
        const std::size_t n = end - begin;
        const aabb& box = bounds.box;
        const auto hand_over = [&](const split* known = nullptr) {
            return build(begin, end, box, depth, known, &bounds.centroids);
        };
        if (n <= options_.max_leaf_size || depth + 1 >= options_.max_depth || budget == 0)
            return hand_over();
        // Cuts across the longest axis only (all three: 3x the cost, slower trees; docs/performance.md exp. 6).
        // No reference wider than a slice there (a fine mesh, the lower tree): build() as it is.
        const vec3 e = box.extent();
        const int axis = e.x >= e.y ? (e.x >= e.z ? 0 : 2) : (e.y >= e.z ? 1 : 2);
        if (!(bounds.widest[axis] > e[axis] / real(slice_count_)))
            return hand_over();
        const bool wide[3] = {axis == 0, axis == 1, axis == 2};
        const split object = find_split(refs, n, bounds.centroids);
        if (object.axis < 0)
            return hand_over(&object);
        const aabb overlap{glm::max(object.left.lo, object.right.lo), glm::min(object.left.hi, object.right.hi)};
        if (overlap.empty() || !(half_area(overlap) > options_.spatial_overlap * root_area))
            return hand_over(&object);
        const spatial_split cut = find_spatial_split(refs, n, box, wide);

        // the pieces go after the node's references, in its room
        std::size_t count = n, middle = 0;
        side_bounds l, r;
        if (cut.axis >= 0 && cut.cost < object.cost && cut.extra <= budget) {
            count += cut_references(refs, n, budget, cut.axis, cut.plane, prims_);
            const auto below = [&](const build_item& item) { return item.box.hi[cut.axis] <= cut.plane; };
            middle = partition_by<true>(refs, count, below, l, r);
            if (middle > 0 && middle < count)
                ++spatial_splits;
        }
        if (middle == 0 || middle == count) { // the object split, as build() makes it
            l = r = side_bounds();
            const auto left_of = [&](const build_item& item) { return object.left_of(item.centroid); };
            middle = partition_by<true>(refs, count, left_of, l, r);
            if (middle == 0 || middle == count) { // pieces of one primitive only (never seen)
                middle = count / 2;
                l = bounds_of(refs, middle);
                r = bounds_of(refs + middle, count - middle);
            }
        }
        pieces += count - n;
        budget -= count - n;

        // The room left is shared by the children in proportion to their
        // references (so the tree does not depend on which is built first),
        // the left child's between the two ranges: the right range moves up.
        const std::size_t right_count = count - middle;
        const std::size_t right_budget = std::size_t(double(budget) * double(right_count) / double(count));
        const std::size_t left_budget = budget - right_budget;
        const std::size_t right_begin = begin + middle + left_budget;
        if (left_budget > 0) { // the first left_budget of the right range go to its end, or all of it moves
            const std::size_t moved = std::min(left_budget, right_count);
            std::uninitialized_copy(refs + middle, refs + middle + moved, refs + count + left_budget - moved);
        }
        return inner_node(
            box, half_area(box), count,
            [&] { return spatial_node(begin, begin + middle, left_budget, depth + 1, root_area, l); },
            [&](binary_builder& b) {
                return b.spatial_node(right_begin, right_begin + right_count, right_budget, depth + 1, root_area, r);
            });
    }

    /// A new node's index, in this builder's run of the store, and `at` the node.
    std::uint32_t new_node(binary_node*& at)
    {
        if (next_node_ == run_end_) {
            next_node_ = nodes_.take_run();
            run_end_ = next_node_ + binary_node_store::run;
            run_at_ = &nodes_[next_node_]; // a run's nodes are consecutive
        }
        at = ::new (static_cast<void*>(run_at_++)) binary_node;
        ++node_count;
        return next_node_++;
    }

    /// A new inner node over `box` (of `area`, n references) with the children
    /// build_left() and build_right(b) make: on two threads from
    /// parallel_threshold references on (build_in_parallel), else here, left first.
    template <class Left, class Right>
    binary_child inner_node(const aabb& box, real area, std::size_t n, const Left& build_left, const Right& build_right)
    {
        binary_node* node = nullptr; // stays where it is (build_store.hpp)
        const std::uint32_t index = new_node(node);
        sah_cost += double(options_.traversal_cost) * double(area);
        binary_child left, right;
        if (n >= parallel_threshold && tasks_ != nullptr) {
            build_in_parallel(left, right, build_left, build_right);
        } else {
            left = build_left();
            right = build_right(*this);
        }
        node->side[0] = left;
        node->side[1] = right;
        binary_child inner;
        inner.box = box;
        inner.index = index;
        return inner;
    }

    /// Builds a node's left child here (build_left()) while its right child
    /// (build_right(b), b a builder over the same stores) is offered to the
    /// other threads (build_tasks.hpp); the right subtree's nodes and items
    /// are in the stores (build_store.hpp) when it joins.
    template <class Left, class Right>
    void build_in_parallel(binary_child& left, binary_child& right, const Left& build_left, const Right& build_right)
    {
        binary_builder right_builder(items_, nodes_, options_, tasks_, prims_);
        auto build_right_here = [&] { right = build_right(right_builder); };
        tasks_->fork(build_right_here, [&] { left = build_left(); });
        node_count += right_builder.node_count;
        sah_cost += right_builder.sah_cost;
        spatial_splits += right_builder.spatial_splits;
        pieces += right_builder.pieces;
    }

    /// From this many primitives a node bins its two halves on two threads.
    static constexpr std::size_t parallel_binning_threshold = 65536;

    /// Whether a node's binning, spatial search and move to the sides run in two halves.
    bool in_halves(std::size_t n) const { return n >= parallel_binning_threshold && tasks_ != nullptr; }

    /// The leaf tests that n primitives cost (leaf_tests, build_options.hpp).
    real tests(std::size_t n) const { return leaf_tests(n, options_.primitives_per_test); }

    split find_split(const build_item* items, std::size_t n, const aabb& centroids)
    {
        const std::size_t used = bins_for(n, bin_count_);
        bins_.reset(centroids, used);
        if (in_halves(n)) {
            if (!other_bins_) // only the top of a large tree bins in halves
                other_bins_ = std::make_unique<sah_bins>(bin_count_, options_.primitives_per_test);
            other_bins_->reset(centroids, used);
            auto second_half = [&] { other_bins_->add(items + n / 2, n - n / 2); };
            tasks_->fork(second_half, [&] { bins_.add(items, n / 2); });
            bins_.merge(*other_bins_);
        } else {
            bins_.add(items, n);
        }
        return bins_.best(n);
    }

    /// The best spatial split of a node's references (spatial_split.hpp),
    /// binned in two halves on two threads from parallel_binning_threshold on.
    spatial_split find_spatial_split(const build_item* refs, std::size_t n, const aabb& box, const bool wide[3])
    {
        if (!spatial_bins_)
            spatial_bins_ = std::make_unique<spatial_bins>(slice_count_);
        spatial_bins& bins = *spatial_bins_;
        bins.reset(box, wide);
        if (in_halves(n)) {
            spatial_bins other(slice_count_);
            other.reset(box, wide);
            auto second_half = [&] { other.add(refs + n / 2, n - n / 2, prims_); };
            tasks_->fork(second_half, [&] { bins.add(refs, n / 2, prims_); });
            bins.merge(other);
        } else {
            bins.add(refs, n, prims_);
        }
        return bins.best(n, options_.primitives_per_test);
    }

    binary_child leaf(std::size_t begin, std::size_t n, const aabb& box, real area)
    {
        // two pieces of one primitive (spatial splits) in one leaf: keep one;
        // the rest of the range stays in items_, referenced by no leaf
        build_item* const first = items_.data() + begin;
        std::sort(first, first + std::ptrdiff_t(n),
                  [](const build_item& x, const build_item& y) { return x.index < y.index; });
        n = std::size_t(std::unique(first, first + std::ptrdiff_t(n),
                                    [](const build_item& x, const build_item& y) { return x.index == y.index; }) -
                        first);
        sah_cost += double(options_.intersection_cost) * double(area) * double(tests(n));
        binary_child c;
        c.box = box;
        c.index = std::uint32_t(begin);
        c.count = std::uint32_t(n);
        return c;
    }

    item_pool& items_;
    binary_node_store& nodes_;
    std::uint32_t next_node_ = 0, run_end_ = 0; ///< this builder's run of nodes_ (new_node)
    binary_node* run_at_ = nullptr;            ///< where nodes_[next_node_] lies
    const bvh_options& options_;
    build_tasks* tasks_; ///< nullptr: one thread
    const packed_primitive* prims_; ///< for clipped_box (spatial splits only)
    std::size_t bin_count_;
    std::size_t slice_count_; ///< the spatial search's slices per axis (bvh_options::spatial_bins)
    sah_bins bins_;
    std::unique_ptr<sah_bins> other_bins_; ///< the second half's, when two threads bin a node
    std::unique_ptr<spatial_bins> spatial_bins_; ///< find_spatial_split's, made at its first search
};

} // namespace detail
} // namespace rt
