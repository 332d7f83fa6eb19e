// bvh/layout.hpp - how the tree sits in memory: wide nodes and leaf blocks.
//
// Why this layout (the measurements are in docs/performance.md, experiment 6):
//  - A node holds the boxes of its children, not its own box (4-wide BVHs:
//    Wald, Benthin, Boulos 2008; Dammertz, Hanika, Keller 2008): one visit tests
//    all its boxes at once, and a ray visits far fewer nodes than in a binary
//    tree. Eight children with AVX2 (one 256-bit register per plane: a third
//    fewer visits than four), four otherwise (one SSE register per plane).
//  - The boxes are stored plane by plane, bounds[lo x / hi x / lo y / ...][child],
//    so one SIMD instruction treats the same plane of all the children.
//    128 bytes in float for four children, 256 for eight: whole cache lines.
//  - A child is an inner node (its index) or a leaf (leaf_flag | its first
//    block, and a count): leaves cost no node of their own. Nodes are stored
//    flat, depth first.
//  - A leaf's triangles are stored four by four as a structure of arrays
//    (triangle_block, 224 bytes), the corners themselves rather than indices,
//    so one SIMD step treats four triangles and a block is one sweep of
//    consecutive cache lines. An unused lane is NaN, which every test refuses.
//  - A block also holds its triangles' unit normals, computed once when it is
//    packed: a closest hit's record reads its normal next to the corners
//    instead of computing it in double at every hit (a separate array of
//    normals missed the cache on incoherent rays).
// (No #pragma once: a unit may compile this file once per width, bvh/dispatch.hpp;
// the guard after the section opens keeps one copy of each.)

#include <cstddef>
#include <cstdint>
#include <limits>

#include "../core/config.hpp"
#include "../scene/triangle_shape.hpp"
#include "../core/vec.hpp"
#include "packed.hpp"

#include "simd_begin.hpp" // RT_BVH_AVX, RT_BVH_AVX2 and the intrinsics, until simd_end.hpp
#if RT_BVH_AVX512 ? !defined(RT_BVH_LAYOUT_W8X) : RT_BVH_AVX2 ? !defined(RT_BVH_LAYOUT_W8) : !defined(RT_BVH_LAYOUT_W4)
#if RT_BVH_AVX512
#define RT_BVH_LAYOUT_W8X
#elif RT_BVH_AVX2
#define RT_BVH_LAYOUT_W8
#else
#define RT_BVH_LAYOUT_W4
#endif

namespace rt {
RT_BVH_ABI_INLINE namespace RT_BVH_ABI { // this width's fast path (bvh/abi_begin.hpp)

/// Children per node: 8 where AVX2 is there (RT_BVH_AVX2), else 4.
constexpr int bvh_width = RT_BVH_AVX2 ? 8 : 4;

} // namespace RT_BVH_ABI

namespace detail {
RT_BVH_ABI_INLINE namespace RT_BVH_ABI { // this width's fast path (bvh/abi_begin.hpp)

using ::rt::RT_BVH_ABI::bvh_width; // this width's, found before rt's inline one

/// Up to four primitives of one leaf as the SIMD leaf test reads them (see the
/// top of this file): the triangles' corners as a structure of arrays,
/// v[3 corner + axis][lane] (row 0 is a.x of the four triangles, row 4 b.y),
/// so that one 4-wide load gives the same coordinate of four triangles, and
/// their ids (packed_primitive::id). A sphere's lane holds its centre and
/// radius in rows 0 to 3, NaN in the others, and sphere_flag in its id, the
/// sign bit of the lane (one movemask finds the spheres of a block). A lane
/// that a leaf does not fill is NaN with id 0. NaN corners give NaN edge
/// functions, which the sign test refuses (and a NaN t, which the range test
/// refuses), so the triangle test needs no mask of its own. n[l] is
/// triangle_normal of lane l's corners (the zero vector for a sphere or an
/// unused lane). 224 bytes in float.
struct alignas(32) triangle_block {
    real v[9][4];
    std::uint32_t id[4];
    vec3 n[4];
};

/// One node (see the top of this file): the boxes of up to bvh_width
/// children, plane by plane, and their references.
struct alignas(64) bvh_node {
    /// bounds[2 k][c] = lo of child c on axis k, bounds[2 k + 1][c] = hi; an
    /// unused child has the empty box lo = +inf, hi = -inf, which no ray meets.
    real bounds[6][bvh_width];
    std::uint32_t child[bvh_width];  ///< an inner child's node index, or leaf_flag | its first primitive
    std::uint32_t count[bvh_width];  ///< a leaf's number of primitives (0 for inner children)
};

/// Set in bvh_node::child for a leaf.
constexpr std::uint32_t leaf_flag = 0x80000000u;

} // namespace RT_BVH_ABI
} // namespace detail

#if defined(RT_BVH_AVX2_SECTION)
// The AVX2 section of bvh/dispatch.hpp opens rt::bvh_w8 and rt::detail::bvh_w8
// as plain namespaces (rt::bvh stays this unit's 4-wide tree), so a name
// looked up from them reaches the inline bvh_w4 before anything else in rt.
// These declarations make them find their own width first: its detail code
// rt's (its bvh_width is declared at the top of its detail section, and a
// using-declaration is found before the enclosing namespaces), and its public
// code, through detail::, its own detail before
// rt::detail (a qualified lookup follows a namespace's using-directives only
// for names it does not hold).
namespace detail {
namespace RT_BVH_ABI {
using namespace ::rt::detail;
} // namespace RT_BVH_ABI
} // namespace detail
namespace RT_BVH_ABI {
namespace detail {
using namespace ::rt::detail::RT_BVH_ABI;
} // namespace detail
} // namespace RT_BVH_ABI
#endif

namespace detail {
RT_BVH_ABI_INLINE namespace RT_BVH_ABI { // this width's fast path (bvh/abi_begin.hpp)

/// triangle_normal (triangle_shape.hpp) of the four lanes of `b` at once, in
/// four lanes of double with AVX: the same operations in the same order, so
/// the same bits (the tests compare the BVH's hit records, which read these
/// normals, with the flat list's, which compute them), and the zero vector
/// for a sphere's or an unused lane (NaN corners, as for corners on one
/// line). A build computes one normal per triangle, four at a time here
/// because the square roots and divisions one at a time were a visible part
/// of a build (docs/performance.md, experiment 6). Returns false where AVX is not there
/// (the caller then calls triangle_normal lane by lane).
inline bool block_normals(triangle_block& b)
{
#if RT_BVH_AVX
    auto row = [&b](int j) { return _mm256_cvtps_pd(_mm_load_ps(b.v[j])); };
    const __m256d ax = row(0), ay = row(1), az = row(2);
    const __m256d e1x = _mm256_sub_pd(row(3), ax), e1y = _mm256_sub_pd(row(4), ay), e1z = _mm256_sub_pd(row(5), az);
    const __m256d e2x = _mm256_sub_pd(row(6), ax), e2y = _mm256_sub_pd(row(7), ay), e2z = _mm256_sub_pd(row(8), az);
    const __m256d nx = _mm256_sub_pd(_mm256_mul_pd(e1y, e2z), _mm256_mul_pd(e1z, e2y));
    const __m256d ny = _mm256_sub_pd(_mm256_mul_pd(e1z, e2x), _mm256_mul_pd(e1x, e2z));
    const __m256d nz = _mm256_sub_pd(_mm256_mul_pd(e1x, e2y), _mm256_mul_pd(e1y, e2x));
    const __m256d magnitude = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
    const __m256d sum = _mm256_add_pd(_mm256_add_pd(_mm256_and_pd(magnitude, nx), _mm256_and_pd(magnitude, ny)),
                                      _mm256_and_pd(magnitude, nz));
    // a normal where 0 < sum < infinity (false for NaN), else the zero vector
    const __m256d has = _mm256_and_pd(_mm256_cmp_pd(sum, _mm256_setzero_pd(), _CMP_GT_OQ),
                                      _mm256_cmp_pd(sum, _mm256_set1_pd(std::numeric_limits<double>::infinity()),
                                                    _CMP_LT_OQ));
    const __m256d squares =
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(nx, nx), _mm256_mul_pd(ny, ny)), _mm256_mul_pd(nz, nz));
    const __m256d inv_length = _mm256_div_pd(_mm256_set1_pd(1.0), _mm256_sqrt_pd(squares));
    alignas(16) float x[4], y[4], z[4];
    _mm_store_ps(x, _mm256_cvtpd_ps(_mm256_and_pd(has, _mm256_mul_pd(nx, inv_length))));
    _mm_store_ps(y, _mm256_cvtpd_ps(_mm256_and_pd(has, _mm256_mul_pd(ny, inv_length))));
    _mm_store_ps(z, _mm256_cvtpd_ps(_mm256_and_pd(has, _mm256_mul_pd(nz, inv_length))));
    for (int lane = 0; lane < 4; ++lane)
        b.n[lane] = vec3(x[lane], y[lane], z[lane]);
    return true;
#else
    (void)b;
    return false;
#endif
}

/// The block of the primitives *lanes[0 .. n), n <= 4.
inline triangle_block pack_triangle_block(const packed_primitive* const lanes[4], std::size_t n)
{
    triangle_block b;
    for (int j = 0; j < 9; ++j)
        for (int lane = 0; lane < 4; ++lane)
            b.v[j][lane] = std::numeric_limits<real>::quiet_NaN();
    for (std::size_t lane = 0; lane < 4; ++lane) {
        b.id[lane] = 0;
        b.n[lane] = vec3(0);
        if (lane >= n)
            continue;
        const packed_primitive& p = *lanes[lane];
        b.id[lane] = p.id;
        for (int j = 0; j < ((p.id & sphere_flag) ? 4 : 9); ++j)
            b.v[j][lane] = p.v[j];
    }
    if (block_normals(b)) // unqualified: this width's
        return b;
    for (std::size_t lane = 0; lane < n && lane < 4; ++lane) {
        const packed_primitive& p = *lanes[lane];
        if (!(p.id & sphere_flag))
            b.n[lane] = triangle_normal(vec3(p.v[0], p.v[1], p.v[2]), vec3(p.v[3], p.v[4], p.v[5]),
                                        vec3(p.v[6], p.v[7], p.v[8]));
    }
    return b;
}

/// The block of prims[first, first + n), n <= 4.
inline triangle_block pack_triangle_block(const packed_primitive* prims, std::size_t first, std::size_t n)
{
    const packed_primitive* lanes[4] = {};
    for (std::size_t lane = 0; lane < n && lane < 4; ++lane)
        lanes[lane] = prims + first + lane;
    return RT_BVH_ABI::pack_triangle_block(lanes, n); // qualified: rt's inline bvh_w4 holds one too (bvh/dispatch.hpp)
}

} // namespace RT_BVH_ABI
} // namespace detail
} // namespace rt

#endif // RT_BVH_LAYOUT_W8X / _W8 / _W4

#include "simd_end.hpp"
