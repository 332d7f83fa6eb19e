// bvh/node_test.hpp - a ray against the four boxes of a node, and the order
// in which the children met are entered.
//
//  - Per ray, the reciprocal direction and, per axis, which plane row of a node
//    is met first are computed once (node_ray), so a box test is a subtraction
//    and a multiplication per plane, no division and no branch: the robust
//    slab test of box_test.hpp, four boxes at once in SSE where it is there.
//  - Closest hit visits the children nearest first. Two are ordered by a
//    select, three or four by ranking their distances in SIMD (order_children),
//    without a branch: on incoherent rays the order is a coin toss that a
//    branch would mispredict (docs/performance.md, experiment 6).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "../config.hpp"
#include "../ray.hpp"
#include "box_test.hpp"
#include "layout.hpp"

#include "simd_begin.hpp" // RT_BVH_SSE, RT_BVH_AVX and the intrinsics, until simd_end.hpp

namespace rt {
namespace detail {

#if RT_BVH_SSE
constexpr bool bvh_uses_sse = true;
#else
constexpr bool bvh_uses_sse = false;
#endif

/// The ray as the node test reads it (see the top of this file).
struct node_ray {
    real origin[3];
    real inv_dir[3];
    /// Per axis, the row of bvh_node::bounds met first (2 k, lo, or 2 k + 1,
    /// hi) and the other, as byte offsets into a node: no index arithmetic per visit.
    std::size_t near_offset[3];
    std::size_t far_offset[3];
#if RT_BVH_SSE
    __m128 origin4[3];   ///< the origin's k-th coordinate in all four lanes
    __m128 inv_dir4[3];  ///< 1/d_k in all four lanes
#endif
};

/// The row of `node`'s bounds at a byte offset of node_ray.
inline const real* bounds_row(const bvh_node& node, std::size_t offset)
{
    return reinterpret_cast<const real*>(reinterpret_cast<const char*>(node.bounds) + offset);
}

inline node_ray make_node_ray(const ray& r)
{
    const box_ray b = make_box_ray(r);
    node_ray n;
    for (int k = 0; k < 3; ++k) {
        n.origin[k] = b.origin[k];
        n.inv_dir[k] = b.inv_dir[k];
        n.near_offset[k] = std::size_t(2 * k + b.negative[k]) * sizeof(bvh_node::bounds[0]);
        n.far_offset[k] = std::size_t(2 * k + 1 - b.negative[k]) * sizeof(bvh_node::bounds[0]);
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
            const real t_near = (bounds_row(node, r.near_offset[k])[c] - r.origin[k]) * r.inv_dir[k];
            const real t_far = (bounds_row(node, r.far_offset[k])[c] - r.origin[k]) * r.inv_dir[k];
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
    auto row = [&node](std::size_t offset) { return _mm_load_ps(bounds_row(node, offset)); };
    const __m128 near_x = _mm_mul_ps(_mm_sub_ps(row(r.near_offset[0]), r.origin4[0]), r.inv_dir4[0]);
    const __m128 far_x = _mm_mul_ps(_mm_sub_ps(row(r.far_offset[0]), r.origin4[0]), r.inv_dir4[0]);
    const __m128 near_y = _mm_mul_ps(_mm_sub_ps(row(r.near_offset[1]), r.origin4[1]), r.inv_dir4[1]);
    const __m128 far_y = _mm_mul_ps(_mm_sub_ps(row(r.far_offset[1]), r.origin4[1]), r.inv_dir4[1]);
    const __m128 near_z = _mm_mul_ps(_mm_sub_ps(row(r.near_offset[2]), r.origin4[2]), r.inv_dir4[2]);
    const __m128 far_z = _mm_mul_ps(_mm_sub_ps(row(r.far_offset[2]), r.origin4[2]), r.inv_dir4[2]);
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

/// The lowest set bit of a 4-bit mask (lowest_bit[0] is 0, never used).
constexpr int lowest_bit[16] = {0, 0, 1, 0, 2, 0, 1, 0, 3, 0, 1, 0, 2, 0, 1, 0};

/// The children met by a ray, nearest first, without a branch (closest hit,
/// see the top of this file): order[0 .. n-1] are the lanes of `mask` by
/// increasing tnear, order[n .. 3] the others; returns n, the number met.
///
/// Each lane gets a key, the bits of its tnear as an integer with the lane
/// number in the two lowest bits (a lane not met gets the largest key). For
/// floats >= 0 the integer order is the float order, and the lane bits make
/// the keys distinct, so a lane's rank (how many keys are smaller) is a
/// permutation of 0 ... 3; order[rank] = lane. Dropping two bits of tnear may
/// reorder children whose entry distances are within 3 ulps, which changes
/// no result: the closest hit is decided by replaces(), not by the order of
/// the visits. (With a negative tmin a negative tnear sorts first: the order
/// is then only approximate, and the result again the same.)
inline int order_children(int mask, const real tnear[4], int order[4])
{
#if RT_BVH_SSE
    const __m128i lane = _mm_set_epi32(3, 2, 1, 0);
    const __m128i bit = _mm_set_epi32(8, 4, 2, 1);
    const __m128i met = _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(mask), bit), bit);
    const __m128i t = _mm_castps_si128(_mm_loadu_ps(tnear));
    const __m128i bits = _mm_or_si128(_mm_and_si128(met, t), _mm_andnot_si128(met, _mm_set1_epi32(0x7fffffff)));
    const __m128i keys = _mm_andnot_si128(_mm_set1_epi32(3), bits); // the two low bits cleared
    const __m128i k = _mm_or_si128(keys, lane);
    // rank = how many of the other three keys are smaller: compare with the
    // keys rotated by one, two and three lanes (cmpgt gives -1 where true)
    const __m128i r1 = _mm_cmpgt_epi32(k, _mm_shuffle_epi32(k, _MM_SHUFFLE(0, 3, 2, 1)));
    const __m128i r2 = _mm_cmpgt_epi32(k, _mm_shuffle_epi32(k, _MM_SHUFFLE(1, 0, 3, 2)));
    const __m128i r3 = _mm_cmpgt_epi32(k, _mm_shuffle_epi32(k, _MM_SHUFFLE(2, 1, 0, 3)));
    const __m128i rank = _mm_sub_epi32(_mm_setzero_si128(), _mm_add_epi32(_mm_add_epi32(r1, r2), r3));
    alignas(16) std::int32_t ranks[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(ranks), rank);
#else
    std::int32_t keys[4], ranks[4];
    for (int c = 0; c < 4; ++c) {
        std::uint32_t bits = 0x7fffffffu;
        if (mask & (1 << c)) {
            const float t = float(tnear[c]);
            std::memcpy(&bits, &t, sizeof bits);
        }
        bits = (bits & ~3u) | std::uint32_t(c);
        keys[c] = std::int32_t(bits);
    }
    for (int c = 0; c < 4; ++c)
        ranks[c] = (keys[(c + 1) & 3] < keys[c]) + (keys[(c + 2) & 3] < keys[c]) + (keys[(c + 3) & 3] < keys[c]);
#endif
    for (int c = 0; c < 4; ++c)
        order[ranks[c]] = c;
    static constexpr int bits_set[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};
    return bits_set[mask & 15];
}

} // namespace detail
} // namespace rt

#include "simd_end.hpp"
