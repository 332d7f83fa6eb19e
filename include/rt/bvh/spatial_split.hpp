// bvh/spatial_split.hpp - planes that cut primitives, for the top of the tree.
//
// Stich, Friedrich, Dietrich, "Spatial Splits in Bounding Volume Hierarchies",
// HPG 2009. A large slanted triangle (a floor, a wall, a column) has a box far
// larger than itself, which overlaps its neighbours' boxes, so no plane between
// centroids separates them and every ray through the box pays for it. A plane
// that cuts such triangles puts each piece, with the box of its part only
// (clipped_box, rounded outwards so it never cuts the triangle), on its side.
// A piece is the same triangle, so a ray gets the same hit through either.
// binary_builder::build_spatial decides where to try it and whether the SAH
// says it pays (docs/performance.md, experiment 6).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <new>
#include <utility>
#include <vector>

#include "../core/aabb.hpp"
#include "../core/config.hpp"
#include "../core/vec.hpp"
#include "build_options.hpp"
#include "packed.hpp"

#include "simd_begin.hpp" // RT_BVH_SSE and the intrinsics, until simd_end.hpp

namespace rt {
namespace detail {

/// Rounds a double to the nearest real below it (down) or above it.
inline real round_outwards(double x, bool down)
{
    real r = real(x);
    if (down && double(r) > x)
        r = std::nextafter(r, -std::numeric_limits<real>::infinity());
    if (!down && double(r) < x)
        r = std::nextafter(r, std::numeric_limits<real>::infinity());
    return r;
}

/// The box of the part of primitive p inside `within` and on one side of the
/// plane x[axis] = s (below: x[axis] <= s, else x[axis] >= s); empty when
/// there is no such part. It never cuts the primitive: a triangle's corners
/// on that side and the points where its edges cross the plane (computed in
/// double, widened by more than their rounding error and rounded outwards),
/// then cut to `within`; a sphere's is `within` cut at the plane.
inline aabb clipped_box(const packed_primitive& p, int axis, real s, bool below, const aabb& within)
{
    aabb box;
    if (p.id & sphere_flag) {
        box = within;
    } else {
        for (int i = 0; i < 3; ++i) {
            const real* u = p.v + 3 * i;
            const real* v = p.v + 3 * ((i + 1) % 3);
            if (below ? u[axis] <= s : u[axis] >= s)
                box.grow(vec3(u[0], u[1], u[2]));
            if ((u[axis] < s && v[axis] > s) || (u[axis] > s && v[axis] < s)) {
                const double t = (double(s) - double(u[axis])) / (double(v[axis]) - double(u[axis]));
                vec3 lo, hi;
                for (int k = 0; k < 3; ++k) {
                    if (k == axis) {
                        lo[k] = hi[k] = s;
                        continue;
                    }
                    const double x = double(u[k]) + t * (double(v[k]) - double(u[k]));
                    const double margin = 16 * std::numeric_limits<double>::epsilon() *
                                          (std::abs(double(u[k])) + std::abs(double(v[k])));
                    lo[k] = round_outwards(x - margin, true);
                    hi[k] = round_outwards(x + margin, false);
                }
                box.grow(lo);
                box.grow(hi);
            }
        }
        box.lo = glm::max(box.lo, within.lo);
        box.hi = glm::min(box.hi, within.hi);
    }
    if (below)
        box.hi[axis] = std::min(box.hi[axis], s);
    else
        box.lo[axis] = std::max(box.lo[axis], s);
    return box;
}

struct spatial_split {
    int axis = -1;
    real plane = 0;
    real cost = 0;          ///< A_L N_L + A_R N_R, as split::cost
    std::size_t extra = 0;  ///< references that would go to both sides
};

/// Cuts the references of items[0, n) that straddle the plane x[axis] =
/// plane into their pieces (clipped_box), in place: the piece below replaces
/// the reference, the piece above goes to items[n], items[n + 1], ... (at most
/// `room`; returns how many), as Embree's builder does in its "extended
/// ranges" (kernels/builders/heuristic_spatial_array.h). A reference with
/// an empty part takes the box of the other. Afterwards a reference lies
/// below the plane (box.hi[axis] <= plane) or reaches above it (one past the
/// room stays whole).
inline std::size_t cut_references(build_item* items, std::size_t n, std::size_t room, int axis, real plane,
                                  const packed_primitive* prims)
{
    std::size_t added = 0;
    for (std::size_t i = 0; i < n; ++i) {
        build_item& r = items[i];
        if (!(r.box.lo[axis] < plane && plane < r.box.hi[axis]))
            continue;
        const aabb below = clipped_box(prims[r.index], axis, plane, true, r.box);
        const aabb above = clipped_box(prims[r.index], axis, plane, false, r.box);
        if (below.empty()) {
            r = build_item{above, above.center(), r.index};
        } else if (above.empty()) {
            r = build_item{below, below.center(), r.index};
        } else if (added < room) {
            ::new (static_cast<void*>(items + n + added++)) build_item{above, above.center(), r.index};
            r = build_item{below, below.center(), r.index};
        }
    }
    return added;
}

/// The bins of the spatial split search of one node: `count` equal slices of
/// the node's box on each axis, with each reference's parts binned where
/// they lie ("chopped binning", Stich et al. sec. 4): a reference spanning
/// several slices adds the box of its part in each slice and counts as
/// entering its first slice and leaving its last. Axes where no reference is
/// wider than a slice (wide[axis] false) are skipped: there a plane cuts next
/// to nothing, and an object split does as well (binary_builder::build_spatial
/// asks for one axis, the node's longest). Bins filled from two parts
/// of the references and merged are the bins of the whole, whatever the
/// order (a box grows by min and max, counts add), so two threads can fill
/// them at the top of the tree.
class spatial_bins {
public:
    /// Bins of `count` slices per axis for any number of searches (reset()),
    /// so that a search allocates nothing (docs/performance.md, exp. 6).
    explicit spatial_bins(std::size_t count)
        : count_(count), slice_(3 * count), enter_(3 * count), leave_(3 * count), planes_(3 * (count + 1)),
          right_box_(count), right_count_(count)
    {
    }

    /// Empty bins over `box`, on the axes where wide[axis].
    void reset(const aabb& box, const bool wide[3])
    {
        active_ = 0;
        const std::size_t count = count_;
        for (int axis = 0; axis < 3; ++axis) {
            const real extent = box.hi[axis] - box.lo[axis];
            if (!wide[axis] || !(extent > 0))
                continue;
            axes_[active_++] = axis;
            low_[axis] = box.lo[axis];
            scale_[axis] = real(count) / extent;
            const std::size_t at = std::size_t(axis) * count;
            std::fill(slice_.begin() + std::ptrdiff_t(at), slice_.begin() + std::ptrdiff_t(at + count), aabb{});
            std::fill(enter_.begin() + std::ptrdiff_t(at), enter_.begin() + std::ptrdiff_t(at + count), std::size_t(0));
            std::fill(leave_.begin() + std::ptrdiff_t(at), leave_.begin() + std::ptrdiff_t(at + count), std::size_t(0));
            for (std::size_t b = 0; b <= count; ++b) // once per axis, not once per crossing
                planes_[std::size_t(axis) * (count + 1) + b] = low_[axis] + extent * real(b) / real(count);
        }
    }

    /// Bins n references, one axis after the other.
    void add(const build_item* refs, std::size_t n, const packed_primitive* prims)
    {
        for (int k = 0; k < active_; ++k)
            add_axis(refs, n, prims, axes_[k]);
    }

    /// Adds the bins of `other`, reset() with the same box and axes.
    void merge(const spatial_bins& other)
    {
        for (int k = 0; k < active_; ++k)
            for (std::size_t b = std::size_t(axes_[k]) * count_, end = b + count_; b < end; ++b) {
                slice_[b].grow(other.slice_[b]);
                enter_[b] += other.enter_[b];
                leave_[b] += other.leave_[b];
            }
    }

    /// Slice b's box on `axis` and the plane below it (slice b lies between
    /// plane(axis, b) and plane(axis, b + 1)), after add(): for the tests.
    const aabb& slice(int axis, std::size_t b) const { return slice_[std::size_t(axis) * count_ + b]; }
    real plane(int axis, std::size_t b) const { return planes_[std::size_t(axis) * (count_ + 1) + b]; }

    /// The plane of least SAH cost for the n references binned.
    spatial_split best(std::size_t n, std::size_t per_test)
    {
        const auto tests = [per_test](std::size_t m) { return leaf_tests(m, per_test); };
        spatial_split best;
        std::vector<aabb>& right_box = right_box_;
        std::vector<std::size_t>& right_count = right_count_;
        for (int k = 0; k < active_; ++k) {
            const int axis = axes_[k];
            const aabb* slice = slice_.data() + std::size_t(axis) * count_;
            const std::size_t* enter = enter_.data() + std::size_t(axis) * count_;
            const std::size_t* leave = leave_.data() + std::size_t(axis) * count_;
            aabb accumulated;
            std::size_t on_right = 0;
            for (std::size_t b = count_ - 1; b > 0; --b) {
                accumulated.grow(slice[b]);
                on_right += leave[b];
                right_box[b] = accumulated;
                right_count[b] = on_right;
            }
            aabb left;
            std::size_t on_left = 0;
            for (std::size_t b = 1; b < count_; ++b) {
                left.grow(slice[b - 1]);
                on_left += enter[b - 1];
                if (on_left == 0 || right_count[b] == 0)
                    continue;
                const real cost = half_area(left) * tests(on_left) + half_area(right_box[b]) * tests(right_count[b]);
                if (best.axis < 0 || cost < best.cost) {
                    best.axis = axis;
                    best.plane = planes_[std::size_t(axis) * (count_ + 1) + b];
                    best.cost = cost;
                    best.extra = on_left + right_count[b] - n;
                }
            }
        }
        return best;
    }

private:
    void add_axis(const build_item* refs, std::size_t n, const packed_primitive* prims, int axis)
    {
        const std::size_t count = count_;
        const real low = low_[axis], scale = scale_[axis];
        const real* planes = planes_.data() + std::size_t(axis) * (count + 1);
        aabb* slice = slice_.data() + std::size_t(axis) * count;
        std::size_t* enter = enter_.data() + std::size_t(axis) * count;
        std::size_t* leave = leave_.data() + std::size_t(axis) * count;
        const auto slot = [&](real x) { return bin_of(x, low, scale, count); };
#if RT_BVH_SSE
        // A reference within one slice (most of them) grows that slice's box
        // in two SSE registers, and the references alternate between two
        // sets of boxes and counts, merged below: neighbouring references
        // fall in the same slice, and each would wait for the last one's
        // store to it (as in sah_bins). Boxes grow by min and max and counts
        // add, so the slices are the same as one set's.
        static_assert(sizeof(aabb) == 6 * sizeof(float), "the loads below read lo.xyz hi.x and hi.xyz then the next float");
        narrow_.assign(2 * count, narrow_box{_mm_set1_ps(std::numeric_limits<float>::infinity()),
                                             _mm_set1_ps(-std::numeric_limits<float>::infinity())});
        narrow_enter_.assign(2 * count, 0);
        narrow_leave_.assign(2 * count, 0);
        std::size_t set = 0; // 0 or count: the set of this reference
#endif
        for (std::size_t i = 0; i < n; ++i) {
            const build_item& r = refs[i];
            const std::size_t first = slot(r.box.lo[axis]), last = slot(r.box.hi[axis]);
#if RT_BVH_SSE
            ++narrow_enter_[set + first];
            ++narrow_leave_[set + last];
            if (first == last) {
                narrow_box& box = narrow_[set + first];
                box.lo = _mm_min_ps(box.lo, _mm_loadu_ps(&r.box.lo.x));
                box.hi = _mm_max_ps(box.hi, _mm_loadu_ps(&r.box.hi.x));
                set ^= count;
                continue;
            }
            set ^= count;
#else
            ++enter[first];
            ++leave[last];
            if (first == last) {
                slice[first].grow(r.box);
                continue;
            }
#endif
            const packed_primitive& p = prims[r.index];
            if (p.id & sphere_flag) { // the slab of the box
                for (std::size_t b = first; b <= last; ++b) {
                    aabb part = r.box;
                    part.lo[axis] = std::max(part.lo[axis], planes[b]);
                    part.hi[axis] = std::min(part.hi[axis], planes[b + 1]);
                    slice[b].grow(part);
                }
                continue;
            }
            // An estimate, for the cost only (the partition uses
            // clipped_box): each corner goes to its slice and each point
            // where an edge crosses a plane to the slices on both sides,
            // all held inside the reference's box.
#if RT_BVH_SSE
            // The same points in SSE without a branch: the three edges in
            // three lanes, each clipped to each slice's slab [s0, s1] by its
            // parameter range there (Liang, Barsky, "A New Concept and Method
            // for Line Clipping", ACM TOG 3(1), 1984); the ends of the pieces
            // are the corners in the slice and the crossings of its planes.
            // Branches on the edges' slices were mispredicted
            // (docs/performance.md, experiment 6).
            const __m128 ux = _mm_setr_ps(p.v[0], p.v[3], p.v[6], p.v[6]);
            const __m128 uy = _mm_setr_ps(p.v[1], p.v[4], p.v[7], p.v[7]);
            const __m128 uz = _mm_setr_ps(p.v[2], p.v[5], p.v[8], p.v[8]);
            const __m128 dx = _mm_sub_ps(_mm_setr_ps(p.v[3], p.v[6], p.v[0], p.v[0]), ux);
            const __m128 dy = _mm_sub_ps(_mm_setr_ps(p.v[4], p.v[7], p.v[1], p.v[1]), uy);
            const __m128 dz = _mm_sub_ps(_mm_setr_ps(p.v[5], p.v[8], p.v[2], p.v[2]), uz);
            const __m128 ua = axis == 0 ? ux : axis == 1 ? uy : uz, da = axis == 0 ? dx : axis == 1 ? dy : dz;
            const __m128 inverse = _mm_div_ps(_mm_set1_ps(1), da); // one division for the three edges
            const __m128 flat = _mm_cmpeq_ps(da, _mm_setzero_ps()); // an edge in a plane of the slices
            const __m128 box_lo = _mm_loadu_ps(&r.box.lo.x), box_hi = _mm_loadu_ps(&r.box.hi.x);
            const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1);
            const __m128 none_lo = _mm_set1_ps(std::numeric_limits<float>::infinity());
            const __m128 none_hi = _mm_set1_ps(-std::numeric_limits<float>::infinity());
            const auto pick = [](__m128 mask, __m128 yes, __m128 no) { // SSE2's select
                return _mm_or_ps(_mm_and_ps(mask, yes), _mm_andnot_ps(mask, no));
            };
            for (std::size_t b = first; b <= last; ++b) {
                const __m128 s0 = _mm_set1_ps(planes[b]), s1 = _mm_set1_ps(planes[b + 1]);
                const __m128 t0 = _mm_mul_ps(_mm_sub_ps(s0, ua), inverse);
                const __m128 t1 = _mm_mul_ps(_mm_sub_ps(s1, ua), inverse);
                __m128 from = _mm_max_ps(zero, _mm_min_ps(t0, t1)), to = _mm_min_ps(one, _mm_max_ps(t0, t1));
                const __m128 in_slab = _mm_and_ps(_mm_cmple_ps(s0, ua), _mm_cmple_ps(ua, s1));
                from = pick(flat, zero, from);
                to = pick(flat, pick(in_slab, one, _mm_set1_ps(-1)), to);
                const __m128 valid = _mm_cmple_ps(from, to); // false for a NaN too
                // the two ends of each edge's piece on one axis, low and high,
                // an invalid lane as the empty box
                const auto ends = [&](__m128 u, __m128 d, __m128& end_lo, __m128& end_hi) {
                    const __m128 p0 = _mm_add_ps(u, _mm_mul_ps(from, d)), p1 = _mm_add_ps(u, _mm_mul_ps(to, d));
                    end_lo = pick(valid, _mm_min_ps(p0, p1), none_lo);
                    end_hi = pick(valid, _mm_max_ps(p0, p1), none_hi);
                };
                __m128 lx, ly, lz, lw = none_lo, hx, hy, hz, hw = none_hi;
                ends(ux, dx, lx, hx);
                ends(uy, dy, ly, hy);
                ends(uz, dz, lz, hz);
                _MM_TRANSPOSE4_PS(lx, ly, lz, lw); // lanes of x, y, z to registers of them
                _MM_TRANSPOSE4_PS(hx, hy, hz, hw);
                const __m128 lo = _mm_min_ps(_mm_min_ps(lx, ly), _mm_min_ps(lz, lw));
                const __m128 hi = _mm_max_ps(_mm_max_ps(hx, hy), _mm_max_ps(hz, hw));
                narrow_box& box = narrow_[set + b]; // held in the reference's box
                box.lo = _mm_min_ps(box.lo, _mm_min_ps(box_hi, _mm_max_ps(box_lo, lo)));
                box.hi = _mm_max_ps(box.hi, _mm_min_ps(box_hi, _mm_max_ps(box_lo, hi)));
            }
#else
            const auto held = [&](const vec3& q) { return glm::clamp(q, r.box.lo, r.box.hi); };
            for (int c = 0; c < 3; ++c) {
                const vec3 u(p.v[3 * c], p.v[3 * c + 1], p.v[3 * c + 2]);
                slice[std::max(first, std::min(last, slot(u[axis])))].grow(held(u));
                const int j = (c + 1) % 3;
                vec3 a = u, b(p.v[3 * j], p.v[3 * j + 1], p.v[3 * j + 2]);
                if (a[axis] > b[axis])
                    std::swap(a, b);
                const std::size_t from = std::max(first, slot(a[axis])), to = std::min(last, slot(b[axis]));
                if (from >= to)
                    continue;
                const real inverse = real(1) / (b[axis] - a[axis]); // one division per edge
                for (std::size_t k = from + 1; k <= to; ++k) {
                    const real s = planes[k];
                    const vec3 q = held(a + (b - a) * ((s - a[axis]) * inverse));
                    slice[k - 1].grow(q);
                    slice[k].grow(q);
                }
            }
#endif
        }
#if RT_BVH_SSE
        for (std::size_t b = 0; b < count; ++b) {
            alignas(16) float lo[4], hi[4];
            for (const std::size_t at : {b, count + b}) {
                _mm_store_ps(lo, narrow_[at].lo);
                _mm_store_ps(hi, narrow_[at].hi);
                slice[b].grow(aabb{vec3(lo[0], lo[1], lo[2]), vec3(hi[0], hi[1], hi[2])});
                enter[b] += narrow_enter_[at];
                leave[b] += narrow_leave_[at];
            }
        }
#endif
    }

    std::size_t count_;
    std::vector<aabb> slice_;                 ///< slice_[axis * count + b]
    std::vector<std::size_t> enter_, leave_;  ///< the same layout
    std::vector<real> planes_;                ///< planes_[axis * (count + 1) + b]: the planes between slices
    std::vector<aabb> right_box_;             ///< best()'s sweep from the right
    std::vector<std::size_t> right_count_;
    int axes_[3] = {0, 0, 0};                 ///< the axes binned, active_ of them
    int active_ = 0;
    real low_[3] = {0, 0, 0}, scale_[3] = {0, 0, 0};
#if RT_BVH_SSE
    struct narrow_box {
        __m128 lo, hi;
    };
    std::vector<narrow_box> narrow_;                       ///< add_axis's two sets of slice boxes
    std::vector<std::size_t> narrow_enter_, narrow_leave_; ///< and counts
#endif
};

} // namespace detail
} // namespace rt

#include "simd_end.hpp"
