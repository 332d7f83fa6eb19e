// bvh/sah_bins.hpp - the bins of a binned SAH split: primitives counted into
// equal slices of their centroids' extent on each axis, and the sweep that
// finds the slice boundary of least cost (binned_builder.hpp uses it).
//
//     rt::detail::sah_bins bins(16, 4);          // 16 slices per axis, leaves of 4
//     bins.reset(centroid_box, rt::detail::bins_for(n, 16));
//     bins.add(items, n);                        // one pass, three axes
//     rt::detail::split best = bins.best(n);     // best.axis < 0: no plane separates them
//
// Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies", IEEE
// Symposium on Interactive Ray Tracing 2007, sec. 3 and 4: binning costs one
// pass over a node's primitives, and the SSE form puts the three axes' slice
// numbers in one register and a bin's box in two (sec. 4.1). Two sets of bins
// filled from two halves of the primitives and merged (merge) are the bins of
// the whole: the top of the tree bins on two threads.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "../core/aabb.hpp"
#include "../core/config.hpp"
#include "../core/vec.hpp"
#include "build_options.hpp"

#include "simd_begin.hpp" // RT_BVH_SSE and the intrinsics, until simd_end.hpp

namespace rt {
namespace detail {

/// A split of a node by the SAH: the axis, where, its cost and the children's boxes.
struct split {
    int axis = -1;
    std::size_t bin = 0;  ///< the first bin of the right side
    real cost = 0;        ///< A_L B(N_L) + A_R B(N_R)
    aabb left, right;
    real low = 0, scale = 0; ///< the bins on `axis`, as bin_of takes them
    std::size_t bins = 0;

    /// Whether an item with this centroid goes to the left child: bin_of(...) <
    /// bin, which for 1 <= bin <= bins - 1 is !(slot >= bin) (a NaN slot is bin 0).
    bool left_of(const vec3& centroid) const { return !((centroid[axis] - low) * scale >= real(bin)); }
};

/// The bins a node of n primitives uses: 4 + n / 20, at most `most`
/// (Embree's binned builder takes min(BINS, 4 + 0.05 n), Embree 3
/// kernels/builders/heuristic_binning.h): a small node has few places worth
/// a plane, and the sweep over the bins costs as much as binning it.
inline std::size_t bins_for(std::size_t n, std::size_t most)
{
    return std::max<std::size_t>(2, std::min(most, 4 + n / 20));
}

/// Bins on three axes for one node (see the top of this file).
class sah_bins {
public:
    /// Bins of up to `count` slices per axis, for any number of nodes (reset()),
    /// in three allocations (a small build's allocations were a tenth of its time).
    sah_bins(std::size_t count, std::size_t per_test)
        : count_(count), per_test_(per_test), boxes_(7 * count), counts_(6 * count), right_cost_(count)
    {
        for (int axis = 0; axis < 3; ++axis) {
            box_[axis] = boxes_.data() + std::size_t(axis) * count;
            odd_box_[axis] = boxes_.data() + std::size_t(3 + axis) * count;
            count_in_[axis] = counts_.data() + std::size_t(axis) * count;
            odd_count_[axis] = counts_.data() + std::size_t(3 + axis) * count;
        }
        right_box_ = boxes_.data() + 6 * count;
    }
    sah_bins(const sah_bins&) = delete; // box_ and the others point into boxes_ and counts_
    sah_bins& operator=(const sah_bins&) = delete;

    /// Where a node's centroids fall, in `used` bins (at most count()): low and
    /// scale per axis (scale 0: the axis has no extent, everything in bin 0,
    /// never split there), and every bin emptied.
    void reset(const aabb& centroids, std::size_t used)
    {
        used_ = std::max<std::size_t>(2, std::min(used, count_));
        for (int axis = 0; axis < 3; ++axis) {
            low_[axis] = centroids.lo[axis];
            const real extent = centroids.hi[axis] - low_[axis];
            scale_[axis] = extent > 0 ? real(used_) / extent : real(0);
            std::fill(box_[axis], box_[axis] + used_, bin_box{});
            std::fill(count_in_[axis], count_in_[axis] + used_, std::uint32_t(0));
        }
    }

    /// Counts n items into the bins (their centroid's bin on each axis).
    void add(const build_item* items, std::size_t n)
    {
#if RT_BVH_SSE
        static_assert(sizeof(aabb) == 6 * sizeof(float) && offsetof(build_item, centroid) == sizeof(aabb) &&
                          offsetof(build_item, index) == offsetof(build_item, centroid) + 3 * sizeof(float),
                      "the loads below read an item as lo.xyz hi.xyz centroid.xyz index");
        // lanes x, y, z (the fourth is never read): a box's corners are loaded
        // from the item as they lie (lo.xyz then hi.x; hi.xyz then the
        // centroid's x), its centroid too, with the index's bits cleared
        const __m128 low = _mm_setr_ps(low_[0], low_[1], low_[2], 0.0f);
        const __m128 scale = _mm_setr_ps(scale_[0], scale_[1], scale_[2], 0.0f);
        const __m128 last = _mm_set1_ps(float(used_ - 1));
        const __m128 xyz = _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0));
        const __m128 zero = _mm_setzero_ps();
        // One set of bins as locals: __m128 may alias anything, so pointers
        // read from the members would be read again after every store to a
        // bin, and a loop over the axes was not unrolled (what this bought:
        // docs/architecture.md, "Figures behind the comments").
        struct bin_set {
            bin_box *x, *y, *z;
            std::uint32_t *nx, *ny, *nz;
        };
        const auto bin_one = [&](const build_item& item, const bin_set& set) {
            const __m128 lo = _mm_loadu_ps(&item.box.lo.x);
            const __m128 hi = _mm_loadu_ps(&item.box.hi.x);
            const __m128 c = _mm_and_ps(_mm_loadu_ps(&item.centroid.x), xyz);
            const __m128 at = _mm_mul_ps(_mm_sub_ps(c, low), scale);
            // max(at, 0) returns 0 for a NaN (its second operand), as bin_of does
            const __m128i slot = _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(at, zero), last));
            const std::size_t sx = std::uint32_t(_mm_cvtsi128_si32(slot));
            const std::size_t sy = std::uint32_t(_mm_cvtsi128_si32(_mm_shuffle_epi32(slot, _MM_SHUFFLE(1, 1, 1, 1))));
            const std::size_t sz = std::uint32_t(_mm_cvtsi128_si32(_mm_shuffle_epi32(slot, _MM_SHUFFLE(2, 2, 2, 2))));
            set.x[sx].lo = _mm_min_ps(set.x[sx].lo, lo);
            set.x[sx].hi = _mm_max_ps(set.x[sx].hi, hi);
            set.y[sy].lo = _mm_min_ps(set.y[sy].lo, lo);
            set.y[sy].hi = _mm_max_ps(set.y[sy].hi, hi);
            set.z[sz].lo = _mm_min_ps(set.z[sz].lo, lo);
            set.z[sz].hi = _mm_max_ps(set.z[sz].hi, hi);
            ++set.nx[sx];
            ++set.ny[sy];
            ++set.nz[sz];
        };
        const bin_set even{box_[0], box_[1], box_[2], count_in_[0], count_in_[1], count_in_[2]};
        std::size_t i = 0;
        if (n >= 4 * used_) {
            // Neighbouring items of a mesh fall in the same bins: each would wait
            // for the last one's store to its bin. Odd items go to a second set
            // of bins, merged at the end, so two such chains run side by side.
            for (int axis = 0; axis < 3; ++axis) {
                std::fill(odd_box_[axis], odd_box_[axis] + used_, bin_box{});
                std::fill(odd_count_[axis], odd_count_[axis] + used_, std::uint32_t(0));
            }
            const bin_set odd{odd_box_[0], odd_box_[1], odd_box_[2], odd_count_[0], odd_count_[1], odd_count_[2]};
            for (; i + 1 < n; i += 2) {
                bin_one(items[i], even);
                bin_one(items[i + 1], odd);
            }
            for (int axis = 0; axis < 3; ++axis)
                for (std::size_t b = 0; b < used_; ++b) {
                    grow(box_[axis][b], odd_box_[axis][b]);
                    count_in_[axis][b] += odd_count_[axis][b];
                }
        }
        for (; i < n; ++i)
            bin_one(items[i], even);
#else
        for (std::size_t i = 0; i < n; ++i) {
            const build_item& item = items[i];
            for (int axis = 0; axis < 3; ++axis) {
                const std::size_t b = bin_of(item.centroid[axis], low_[axis], scale_[axis], used_);
                box_[axis][b].grow(item.box);
                ++count_in_[axis][b];
            }
        }
#endif
    }

    /// Adds another node's bins, filled with the same reset(), to these.
    void merge(const sah_bins& other)
    {
        for (int axis = 0; axis < 3; ++axis)
            for (std::size_t b = 0; b < used_; ++b) {
                grow(box_[axis][b], other.box_[axis][b]);
                count_in_[axis][b] += other.count_in_[axis][b];
            }
    }

    /// The boundary of least A_L B(N_L) + A_R B(N_R) over the three axes, for
    /// the n items added; axis -1 when every item is in one bin on every axis.
    split best(std::size_t n)
    {
        split best;
        for (int axis = 0; axis < 3; ++axis) {
            if (scale_[axis] == 0)
                continue;
            // sweep from the right: right_cost_[s] = A_R B(N_R) for the split before bin s
            bin_box accumulated;
            std::size_t on_right = 0;
            for (std::size_t s = used_ - 1; s > 0; --s) {
                grow(accumulated, box_[axis][s]);
                on_right += count_in_[axis][s];
                right_box_[s] = accumulated;
                right_cost_[s] = area_of(accumulated) * leaf_tests(on_right, per_test_);
            }
            bin_box left;
            std::size_t on_left = 0;
            for (std::size_t s = 1; s < used_; ++s) {
                grow(left, box_[axis][s - 1]);
                on_left += count_in_[axis][s - 1];
                if (on_left == 0 || on_left == n)
                    continue;
                const real cost = area_of(left) * leaf_tests(on_left, per_test_) + right_cost_[s];
                if (best.axis < 0 || cost < best.cost) {
                    best.axis = axis;
                    best.bin = s;
                    best.cost = cost;
                    best.left = to_aabb(left);
                    best.right = to_aabb(right_box_[s]);
                }
            }
        }
        if (best.axis >= 0) {
            best.low = low_[best.axis];
            best.scale = scale_[best.axis];
            best.bins = used_;
        }
        return best;
    }

private:
#if RT_BVH_SSE
    struct bin_box {
        __m128 lo = _mm_set1_ps(std::numeric_limits<float>::infinity());
        __m128 hi = _mm_set1_ps(-std::numeric_limits<float>::infinity());
    };
    static void grow(bin_box& box, const bin_box& by)
    {
        box.lo = _mm_min_ps(box.lo, by.lo);
        box.hi = _mm_max_ps(box.hi, by.hi);
    }
    /// half_area of a box that is not empty: (x y + y z) + z x, as half_area sums it
    static real area_of(const bin_box& box)
    {
        const __m128 e = _mm_sub_ps(box.hi, box.lo);
        const __m128 p = _mm_mul_ps(e, _mm_shuffle_ps(e, e, _MM_SHUFFLE(3, 0, 2, 1))); // xy yz zx
        return _mm_cvtss_f32(_mm_add_ss(_mm_add_ss(p, _mm_shuffle_ps(p, p, 1)), _mm_movehl_ps(p, p)));
    }
    static aabb to_aabb(const bin_box& box)
    {
        alignas(16) float lo[4], hi[4];
        _mm_store_ps(lo, box.lo);
        _mm_store_ps(hi, box.hi);
        aabb out;
        out.lo = vec3(lo[0], lo[1], lo[2]);
        out.hi = vec3(hi[0], hi[1], hi[2]);
        return out;
    }
#else
    using bin_box = aabb;
    static void grow(bin_box& box, const bin_box& by) { box.grow(by); }
    static real area_of(const bin_box& box) { return half_area(box); }
    static aabb to_aabb(const bin_box& box) { return box; }
#endif

    std::size_t count_, per_test_, used_ = 2;
    real low_[3] = {0, 0, 0}, scale_[3] = {0, 0, 0};
    std::vector<bin_box> boxes_;         ///< box_, odd_box_, right_box_
    std::vector<std::uint32_t> counts_;  ///< count_in_, odd_count_
    std::vector<real> right_cost_;
    bin_box* box_[3];                    ///< box_[axis][bin]
    bin_box* odd_box_[3];                ///< the odd items' bins, while add() runs (SSE only)
    bin_box* right_box_;
    std::uint32_t* count_in_[3];
    std::uint32_t* odd_count_[3];
};

/// What one side of a partition holds: its items' box, their centroids' box
/// and, for build_spatial, their widest extent on each axis (a plane cuts a
/// reference only on an axis where it is wider than a slice).
struct side_bounds {
    aabb box, centroids;
    vec3 widest{0};

    /// One item (scalar: where the item was just written, an SSE load of it
    /// would wait for the stores, as side_gatherer's would).
    void add(const build_item& item)
    {
        box.grow(item.box);
        centroids.grow(item.centroid);
        widest = glm::max(widest, item.box.hi - item.box.lo);
    }

    void merge(const side_bounds& other)
    {
        box.grow(other.box);
        centroids.grow(other.centroids);
        widest = glm::max(widest, other.widest);
    }
};

/// side_bounds gathered item by item while the items are moved to their
/// side, in SSE registers where there are (lanes x, y, z, as sah_bins::add
/// loads an item); `with_widest` false leaves widest alone.
template <bool with_widest>
class side_gatherer {
public:
#if RT_BVH_SSE
    void take(const build_item& item)
    {
        const __m128 lo = _mm_loadu_ps(&item.box.lo.x), hi = _mm_loadu_ps(&item.box.hi.x);
        const __m128 c = _mm_and_ps(_mm_loadu_ps(&item.centroid.x), xyz());
        lo_ = _mm_min_ps(lo_, lo);
        hi_ = _mm_max_ps(hi_, hi);
        clo_ = _mm_min_ps(clo_, c);
        chi_ = _mm_max_ps(chi_, c);
        if (with_widest)
            widest_ = _mm_max_ps(widest_, _mm_and_ps(_mm_sub_ps(hi, lo), xyz()));
    }

    /// Adds what was gathered to `out`.
    void finish(side_bounds& out) const
    {
        side_bounds mine;
        mine.box = aabb{lanes(lo_), lanes(hi_)};
        mine.centroids = aabb{lanes(clo_), lanes(chi_)};
        if (with_widest)
            mine.widest = lanes(widest_);
        out.merge(mine);
    }

private:
    static __m128 xyz() { return _mm_castsi128_ps(_mm_setr_epi32(-1, -1, -1, 0)); }
    static vec3 lanes(__m128 v)
    {
        alignas(16) float a[4];
        _mm_store_ps(a, v);
        return vec3(a[0], a[1], a[2]);
    }
    __m128 lo_ = _mm_set1_ps(std::numeric_limits<float>::infinity()), clo_ = lo_;
    __m128 hi_ = _mm_set1_ps(-std::numeric_limits<float>::infinity()), chi_ = hi_;
    __m128 widest_ = _mm_setzero_ps();
#else
    void take(const build_item& item)
    {
        if (with_widest) {
            mine_.add(item);
        } else {
            mine_.box.grow(item.box);
            mine_.centroids.grow(item.centroid);
        }
    }
    void finish(side_bounds& out) const { out.merge(mine_); }

private:
    side_bounds mine_;
#endif
};

/// The bounds of n items, in one pass in registers (side_gatherer; gathered
/// while they were pushed to their side, they were stored and reloaded
/// around every push_back).
inline side_bounds bounds_of(const build_item* items, std::size_t n)
{
    side_gatherer<true> on;
    for (std::size_t i = 0; i < n; ++i)
        on.take(items[i]);
    side_bounds out;
    on.finish(out);
    return out;
}

/// Moves the items that is_left(item) sends left before the others and
/// returns how many went left; `left` and `right` receive each side's bounds,
/// found in the same pass (the children's boxes are their items', whatever the
/// bins said, and their centroid boxes need no pass of their own); their
/// widest extents only `with_widest`.
template <bool with_widest, class IsLeft>
std::size_t partition_by(build_item* items, std::size_t n, const IsLeft& is_left, side_bounds& left,
                         side_bounds& right)
{
    side_gatherer<with_widest> on[2]; // [0] left, [1] right
    std::size_t i = 0, j = n;
    for (;;) {
        while (i < j && is_left(items[i]))
            on[0].take(items[i++]);
        while (i < j && !is_left(items[j - 1]))
            on[1].take(items[--j]);
        if (i == j)
            break;
        std::swap(items[i], items[j - 1]); // then both loops take them
    }
    on[0].finish(left);
    on[1].finish(right);
    return i;
}

/// partition_by the side of the split s.
inline std::size_t partition_items(build_item* items, std::size_t n, const split& s, side_bounds& left,
                                   side_bounds& right)
{
    return partition_by<false>(items, n, [&](const build_item& item) { return s.left_of(item.centroid); }, left,
                               right);
}

} // namespace detail
} // namespace rt

#include "simd_end.hpp"
