// bvh/node_test.hpp - a ray against the boxes of a node's children.
//
// Per ray, the reciprocal direction and, per axis, which plane row of a node
// is met first are computed once (node_ray), so a box test is a subtraction
// and a multiplication per plane, no division and no branch: the robust slab
// test of box_test.hpp, the eight boxes of a node at once in AVX2, or its four
// in SSE, or one at a time (the reference the tests compare them with).
// Which of the children met a ray enters, and in what order: descend.hpp.
// (No #pragma once: a unit may compile this file once per width, bvh/dispatch.hpp;
// the guard after the section opens keeps one copy of each.)

#include <cstddef>
#include <cstdint>

#include "../core/config.hpp"
#include "../core/ray.hpp"
#include "box_test.hpp"
#include "layout.hpp"

#include "simd_begin.hpp" // RT_BVH_SSE, RT_BVH_AVX2 and the intrinsics, until simd_end.hpp
#if RT_BVH_AVX512 ? !defined(RT_BVH_NODE_TEST_W8X) : RT_BVH_AVX2 ? !defined(RT_BVH_NODE_TEST_W8) : !defined(RT_BVH_NODE_TEST_W4)
#if RT_BVH_AVX512
#define RT_BVH_NODE_TEST_W8X
#elif RT_BVH_AVX2
#define RT_BVH_NODE_TEST_W8
#else
#define RT_BVH_NODE_TEST_W4
#endif

namespace rt {
namespace detail {
RT_BVH_ABI_INLINE namespace RT_BVH_ABI { // this width's fast path (bvh/abi_begin.hpp)

// this section's own node, also in bvh/dispatch.hpp's second section
static_assert(bvh_width == (RT_BVH_AVX2 ? 8 : 4) && sizeof(bvh_node::child) == bvh_width * sizeof(std::uint32_t),
              "expected the node of this section's width (bvh/layout.hpp)");

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
#if RT_BVH_AVX2
    __m256 origin8[3];   ///< the origin's k-th coordinate in all eight lanes
    __m256 inv_dir8[3];  ///< 1/d_k in all eight lanes
#elif RT_BVH_SSE
    __m128 origin4[3];   ///< the origin's k-th coordinate in all four lanes
    __m128 inv_dir4[3];  ///< 1/d_k in all four lanes
#endif
};

/// The row of `node`'s bounds at a byte offset of node_ray.
inline const real* bounds_row(const bvh_node& node, std::size_t offset)
{
    return reinterpret_cast<const real*>(reinterpret_cast<const char*>(node.bounds) + offset);
}

RT_BVH_INLINE node_ray make_node_ray(const ray& r)
{
    const box_ray b = make_box_ray(r);
    node_ray n;
    for (int k = 0; k < 3; ++k) {
        n.origin[k] = b.origin[k];
        n.inv_dir[k] = b.inv_dir[k];
        n.near_offset[k] = std::size_t(2 * k + b.negative[k]) * sizeof(bvh_node::bounds[0]);
        n.far_offset[k] = std::size_t(2 * k + 1 - b.negative[k]) * sizeof(bvh_node::bounds[0]);
#if RT_BVH_AVX2
        n.origin8[k] = _mm256_set1_ps(float(b.origin[k]));
        n.inv_dir8[k] = _mm256_set1_ps(float(b.inv_dir[k]));
#elif RT_BVH_SSE
        n.origin4[k] = _mm_set1_ps(float(b.origin[k]));
        n.inv_dir4[k] = _mm_set1_ps(float(b.inv_dir[k]));
#endif
    }
    return n;
}

/// The slab test of hit_box for the children of `node` at once: bit c of the
/// result is set when child c is met in [tmin, tmax], and tnear[c] is then
/// where the ray enters it. One value at a time.
inline int intersect_children_scalar(const bvh_node& node, const node_ray& r, real tmin, real tmax,
                                     real tnear[bvh_width])
{
    int mask = 0;
    for (int c = 0; c < bvh_width; ++c) {
        real t0 = tmin, t1 = tmax;
        for (int k = 0; k < 3; ++k) {
            const real t_near = (bounds_row(node, r.near_offset[k])[c] - r.origin[k]) * r.inv_dir[k];
            const real t_far = (bounds_row(node, r.far_offset[k])[c] - r.origin[k]) * r.inv_dir[k];
            t0 = t_near > t0 ? t_near : t0; // a NaN keeps the interval (see hit_box)
            t1 = t_far < t1 ? t_far : t1;
        }
        tnear[c] = t0;
        mask |= (t0 <= t1 * slab_robust_far_factor ? 1 : 0) << c;
    }
    return mask;
}

#if RT_BVH_AVX2
/// The same test with AVX, one child per lane, as intersect_children_sse.
inline int intersect_children_avx2(const bvh_node& node, const node_ray& r, float tmin, float tmax, float tnear[8])
{
    auto row = [&node](std::size_t offset) { return _mm256_load_ps(bounds_row(node, offset)); };
    const __m256 near_x = _mm256_mul_ps(_mm256_sub_ps(row(r.near_offset[0]), r.origin8[0]), r.inv_dir8[0]);
    const __m256 far_x = _mm256_mul_ps(_mm256_sub_ps(row(r.far_offset[0]), r.origin8[0]), r.inv_dir8[0]);
    const __m256 near_y = _mm256_mul_ps(_mm256_sub_ps(row(r.near_offset[1]), r.origin8[1]), r.inv_dir8[1]);
    const __m256 far_y = _mm256_mul_ps(_mm256_sub_ps(row(r.far_offset[1]), r.origin8[1]), r.inv_dir8[1]);
    const __m256 near_z = _mm256_mul_ps(_mm256_sub_ps(row(r.near_offset[2]), r.origin8[2]), r.inv_dir8[2]);
    const __m256 far_z = _mm256_mul_ps(_mm256_sub_ps(row(r.far_offset[2]), r.origin8[2]), r.inv_dir8[2]);
    const __m256 t0 = _mm256_max_ps(near_z, _mm256_max_ps(near_y, _mm256_max_ps(near_x, _mm256_set1_ps(tmin))));
    const __m256 t1 = _mm256_min_ps(far_z, _mm256_min_ps(far_y, _mm256_min_ps(far_x, _mm256_set1_ps(tmax))));
    _mm256_store_ps(tnear, t0);
    return _mm256_movemask_ps(_mm256_cmp_ps(t0, _mm256_mul_ps(t1, _mm256_set1_ps(float(slab_robust_far_factor))), _CMP_LE_OQ));
}
#elif RT_BVH_SSE
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
    return _mm_movemask_ps(_mm_cmple_ps(t0, _mm_mul_ps(t1, _mm_set1_ps(float(slab_robust_far_factor)))));
}
#endif

/// tnear must be aligned to 32 bytes (the AVX2 test stores it whole).
inline int intersect_children(const bvh_node& node, const node_ray& r, real tmin, real tmax, real tnear[bvh_width])
{
#if RT_BVH_AVX2
    return intersect_children_avx2(node, r, tmin, tmax, tnear);
#elif RT_BVH_SSE
    return intersect_children_sse(node, r, tmin, tmax, tnear);
#else
    return intersect_children_scalar(node, r, tmin, tmax, tnear);
#endif
}

} // namespace RT_BVH_ABI
} // namespace detail
} // namespace rt

#endif // RT_BVH_NODE_TEST_W8X / _W8 / _W4

#include "simd_end.hpp"
