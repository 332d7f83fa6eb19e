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
// says it pays: on Sponza and Sibenik, never on meshes of small triangles
// (docs/performance.md, experiment 6).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "../aabb.hpp"
#include "../config.hpp"
#include "../vec.hpp"
#include "build_options.hpp"
#include "packed.hpp"

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

/// The best plane between `bins` equal slices of the node's box, on any
/// axis, with each reference's parts binned where they lie ("chopped
/// binning", Stich et al. sec. 4): a reference spanning several slices
/// adds the box of its part in each slice (clipped_box) and counts as
/// entering its first slice and leaving its last.
/// Axes where no reference is wider than a slice (wide[axis] false) are
/// skipped: there a plane cuts next to nothing, and an object split
/// does as well.
inline spatial_split find_spatial_split(const std::vector<build_item>& refs, const aabb& box, const bool wide[3],
                                        std::size_t count, const packed_primitive* prims, std::size_t per_test)
{
    const auto tests = [per_test](std::size_t n) { return leaf_tests(n, per_test); };
    spatial_split best;
    std::vector<aabb> slice(count), right_box(count);
    std::vector<std::size_t> enter(count), leave(count), right_count(count);
    std::vector<real> planes(count + 1);
    for (int axis = 0; axis < 3; ++axis) {
        const real low = box.lo[axis], extent = box.hi[axis] - box.lo[axis];
        if (!wide[axis] || !(extent > 0))
            continue;
        const real scale = real(count) / extent;
        for (std::size_t b = 0; b <= count; ++b) // once per axis, not once per crossing
            planes[b] = low + extent * real(b) / real(count);
        const auto plane = [&](std::size_t b) { return planes[b]; };
        const auto slot = [&](real x) { return bin_of(x, low, scale, count); };
        std::fill(slice.begin(), slice.end(), aabb{});
        std::fill(enter.begin(), enter.end(), 0);
        std::fill(leave.begin(), leave.end(), 0);
        for (const build_item& r : refs) {
            const std::size_t first = slot(r.box.lo[axis]), last = slot(r.box.hi[axis]);
            ++enter[first];
            ++leave[last];
            if (first == last) {
                slice[first].grow(r.box);
                continue;
            }
            const packed_primitive& p = prims[r.index];
            if (p.id & sphere_flag) { // the slab of the box
                for (std::size_t b = first; b <= last; ++b) {
                    aabb part = r.box;
                    part.lo[axis] = std::max(part.lo[axis], plane(b));
                    part.hi[axis] = std::min(part.hi[axis], plane(b + 1));
                    slice[b].grow(part);
                }
                continue;
            }
            // An estimate, for the cost only (the partition uses
            // clipped_box): each corner goes to its slice and each point
            // where an edge crosses a plane to the slices on both sides,
            // all held inside the reference's box.
            const auto held = [&](const vec3& q) { return glm::clamp(q, r.box.lo, r.box.hi); };
            for (int i = 0; i < 3; ++i) {
                const vec3 u(p.v[3 * i], p.v[3 * i + 1], p.v[3 * i + 2]);
                slice[std::max(first, std::min(last, slot(u[axis])))].grow(held(u));
                const int j = (i + 1) % 3;
                vec3 a = u, b(p.v[3 * j], p.v[3 * j + 1], p.v[3 * j + 2]);
                if (a[axis] > b[axis])
                    std::swap(a, b);
                const std::size_t from = std::max(first, slot(a[axis])), to = std::min(last, slot(b[axis]));
                if (from >= to)
                    continue;
                const real inverse = real(1) / (b[axis] - a[axis]); // one division per edge
                for (std::size_t k = from + 1; k <= to; ++k) {
                    const real s = plane(k);
                    const vec3 q = held(a + (b - a) * ((s - a[axis]) * inverse));
                    slice[k - 1].grow(q);
                    slice[k].grow(q);
                }
            }
        }
        aabb accumulated;
        std::size_t on_right = 0;
        for (std::size_t b = count - 1; b > 0; --b) {
            accumulated.grow(slice[b]);
            on_right += leave[b];
            right_box[b] = accumulated;
            right_count[b] = on_right;
        }
        aabb left;
        std::size_t on_left = 0;
        for (std::size_t b = 1; b < count; ++b) {
            left.grow(slice[b - 1]);
            on_left += enter[b - 1];
            if (on_left == 0 || right_count[b] == 0)
                continue;
            const real cost = half_area(left) * tests(on_left) + half_area(right_box[b]) * tests(right_count[b]);
            if (best.axis < 0 || cost < best.cost) {
                best.axis = axis;
                best.plane = plane(b);
                best.cost = cost;
                best.extra = on_left + right_count[b] - refs.size();
            }
        }
    }
    return best;
}

} // namespace detail
} // namespace rt
