// bvh/leaf_test.hpp - the watertight test of a leaf block's four triangles at
// once.
//
// The same arithmetic as intersect_watertight (watertight.hpp), lane by lane
// and operation for operation in the same order, so the SIMD test and the
// scalar one give the same bits: the tests compare them on rays through shared
// edges and vertices. With SSE2 (every x86-64 compiler) the four triangles of a
// block are tested in 4-wide registers (certain misses rejected in float, the
// edge functions of a block with a possible hit computed in double, two lanes
// per register or four with AVX); elsewhere, and for rt::real = double, one
// lane at a time (intersect_block_scalar).
// (No #pragma once: a unit may compile this file once per width, bvh/dispatch.hpp;
// the guard after the section opens keeps one copy of each.)

#include <cstdint>
#include <limits>

#include "../core/config.hpp"
#include "../core/rounding.hpp"
#include "../intersection/watertight.hpp"
#include "layout.hpp"
#include "packed.hpp"

#include "simd_begin.hpp" // RT_BVH_SSE, RT_BVH_AVX and the intrinsics, until simd_end.hpp
#if RT_BVH_AVX512 ? !defined(RT_BVH_LEAF_TEST_W8X) : RT_BVH_AVX2 ? !defined(RT_BVH_LEAF_TEST_W8) : !defined(RT_BVH_LEAF_TEST_W4)
#if RT_BVH_AVX512
#define RT_BVH_LEAF_TEST_W8X
#elif RT_BVH_AVX2
#define RT_BVH_LEAF_TEST_W8
#else
#define RT_BVH_LEAF_TEST_W4
#endif

namespace rt {
namespace detail {
RT_BVH_ABI_INLINE namespace RT_BVH_ABI { // this width's fast path (bvh/abi_begin.hpp)

/// The ray as the SIMD leaf test reads it, besides the watertight ray itself:
/// the origin and the shear in all four lanes.
struct leaf_ray {
#if RT_BVH_SSE
    __m128 px, py, pz;  ///< p_kx, p_ky, p_kz
    __m128 Sx, Sy, Sz;
#endif
};

inline leaf_ray make_leaf_ray(const watertight_ray& w)
{
    leaf_ray r;
#if RT_BVH_SSE
    r.px = _mm_set1_ps(float(w.p[w.kx]));
    r.py = _mm_set1_ps(float(w.p[w.ky]));
    r.pz = _mm_set1_ps(float(w.p[w.kz]));
    r.Sx = _mm_set1_ps(float(w.Sx));
    r.Sy = _mm_set1_ps(float(w.Sy));
    r.Sz = _mm_set1_ps(float(w.Sz));
#else
    (void)w; // the scalar test reads the watertight ray alone
#endif
    return r;
}

/// The watertight test of the triangles of block `b`, one lane at a time:
/// each lane's corners are gathered and handed to intersect_watertight. Bit l
/// of the result is set when lane l is hit in [tmin, tmax], and hits[l] is
/// then its hit. Sphere lanes are left to the caller. The fallback where SSE
/// is missing, and the reference the tests compare intersect_block_sse with.
inline int intersect_block_scalar(const triangle_block& b, const watertight_ray& w, real tmin, real tmax,
                                  triangle_hit hits[4])
{
    int mask = 0;
    for (int lane = 0; lane < 4; ++lane) {
        if (b.id[lane] & sphere_flag)
            continue;
        real v[9];
        for (int j = 0; j < 9; ++j)
            v[j] = b.v[j][lane];
        if (intersect_watertight(w, v, tmin, tmax, hits[lane])) // NaN (unused) lanes miss
            mask |= 1 << lane;
    }
    return mask;
}

/// A block's hits lane by lane, as the SIMD test stores them (t[l] is lane
/// l's t): four stores for the four lanes, and nothing written for a block
/// that no lane hits.
struct block_hits {
    alignas(16) real t[4];
    alignas(16) real b0[4];
    alignas(16) real b1[4];
    alignas(16) real b2[4];
};

/// intersect_block_scalar, its hits as block_hits.
inline int intersect_block_scalar(const triangle_block& b, const watertight_ray& w, real tmin, real tmax,
                                  block_hits& hits)
{
    triangle_hit lanes[4];
    const int mask = intersect_block_scalar(b, w, tmin, tmax, lanes);
    for (int lane = 0; lane < 4; ++lane)
        if (mask & (1 << lane)) {
            hits.t[lane] = lanes[lane].t;
            hits.b0[lane] = lanes[lane].b0;
            hits.b1[lane] = lanes[lane].b1;
            hits.b2[lane] = lanes[lane].b2;
        }
    return mask;
}

/// The lane of `mask` (not 0) whose hit a closest-hit search keeps, by the
/// rule of replaces() (packed.hpp): the smallest t, at an equal t the largest
/// id. The smallest t is found in SIMD and the ids are read only on a tie, so
/// a block costs one decision against the closest hit so far, not a branch
/// per lane (on incoherent rays which lanes hit is a coin toss).
inline int closest_lane(int mask, const block_hits& hits, const triangle_block& b)
{
    static constexpr signed char lowest[16] = {0, 0, 1, 0, 2, 0, 1, 0, 3, 0, 1, 0, 2, 0, 1, 0};
#if RT_BVH_SSE
    const __m128i bit = _mm_set_epi32(8, 4, 2, 1);
    const __m128 met = _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(mask), bit), bit));
    const __m128 t = _mm_or_ps(_mm_and_ps(met, _mm_load_ps(hits.t)),
                               _mm_andnot_ps(met, _mm_set1_ps(std::numeric_limits<float>::infinity())));
    __m128 smallest = _mm_min_ps(t, _mm_shuffle_ps(t, t, _MM_SHUFFLE(2, 3, 0, 1)));
    smallest = _mm_min_ps(smallest, _mm_shuffle_ps(smallest, smallest, _MM_SHUFFLE(1, 0, 3, 2)));
    int at_smallest = _mm_movemask_ps(_mm_cmpeq_ps(t, smallest)) & mask;
#else
    real smallest = std::numeric_limits<real>::infinity();
    for (int lane = 0; lane < 4; ++lane)
        if ((mask & (1 << lane)) && hits.t[lane] < smallest)
            smallest = hits.t[lane];
    int at_smallest = 0;
    for (int lane = 0; lane < 4; ++lane)
        at_smallest |= ((mask & (1 << lane)) && hits.t[lane] == smallest) ? 1 << lane : 0;
#endif
    int lane = lowest[at_smallest & 15];
    for (at_smallest &= at_smallest - 1; at_smallest != 0; at_smallest &= at_smallest - 1) { // a tie: rare
        const int other = lowest[at_smallest & 15];
        lane = b.id[other] > b.id[lane] ? other : lane;
    }
    return lane;
}

/// The lanes of `b` that hold spheres (bit l for lane l).
inline int sphere_lanes(const triangle_block& b)
{
#if RT_BVH_SSE
    return _mm_movemask_ps(_mm_castsi128_ps(_mm_load_si128(reinterpret_cast<const __m128i*>(b.id))));
#else
    int mask = 0;
    for (int lane = 0; lane < 4; ++lane)
        mask |= (b.id[lane] & sphere_flag) ? 1 << lane : 0;
    return mask;
#endif
}

#if RT_BVH_SSE
/// Four floats widened to double: one AVX register, or two SSE2 registers
/// (the low pair, then the high pair). Each sheared coordinate is widened once
/// and serves two edge functions.
struct wide4 {
#if RT_BVH_AVX
    __m256d all;
#else
    __m128d lo, hi;
#endif
};

inline wide4 widen(__m128 a)
{
#if RT_BVH_AVX
    return wide4{_mm256_cvtps_pd(a)};
#else
    return wide4{_mm_cvtps_pd(a), _mm_cvtps_pd(_mm_movehl_ps(a, a))};
#endif
}

/// a b - c d for four lanes, each product and the difference in double, the
/// result rounded to float: what intersect_watertight computes for a triangle
/// it may hit, lane by lane, bit for bit (a product of two floats is exact in
/// double, and the difference is rounded to double then to float in both).
inline __m128 edge_function4(const wide4& a, const wide4& b, const wide4& c, const wide4& d)
{
#if RT_BVH_AVX
    return _mm256_cvtpd_ps(_mm256_sub_pd(_mm256_mul_pd(a.all, b.all), _mm256_mul_pd(c.all, d.all)));
#else
    const __m128d lo = _mm_sub_pd(_mm_mul_pd(a.lo, b.lo), _mm_mul_pd(c.lo, d.lo));
    const __m128d hi = _mm_sub_pd(_mm_mul_pd(a.hi, b.hi), _mm_mul_pd(c.hi, d.hi));
    return _mm_movelh_ps(_mm_cvtpd_ps(lo), _mm_cvtpd_ps(hi));
#endif
}

/// a b for four lanes, rounded to float and never fused with what uses it:
/// detail::rounded_product (watertight.hpp) four lanes at a time.
inline __m128 rounded_product4(__m128 a, __m128 b)
{
    __m128 p = _mm_mul_ps(a, b);
#if defined(__GNUC__) || defined(__clang__)
    __asm__("" : "+x"(p));
#endif
    return p;
}

/// max_abs3 (watertight.hpp) of four lanes: the largest of |p|, |q|, |s|.
inline __m128 max_abs3_sse(__m128 p, __m128 q, __m128 s)
{
    const __m128 sign = _mm_set1_ps(-0.0f);
    return _mm_max_ps(_mm_max_ps(_mm_andnot_ps(sign, p), _mm_andnot_ps(sign, q)), _mm_andnot_ps(sign, s));
}

/// The watertight test of four triangles at once, one per lane: the same
/// arithmetic as intersect_watertight and watertight_finish (translation,
/// shear, certain misses rejected in float, the edge functions in double, the
/// sign test, det, T, t, the range, the
/// distance check of watertight_t_error and the barycentrics), operation for
/// operation in the same order, so each lane computes the same bits and
/// intersect_block_scalar gives the same result (tests/stage04_triangle.cpp
/// checks it on rays through shared edges and vertices). Only a lane whose t is
/// within its error bound leaves SIMD, for t_beyond_error_in_double. Needs
/// -ffp-contract=off on FMA targets, as the scalar test does: a fused
/// multiply-add would round the shear differently here and there. With
/// `with_hits` false (any hit) only the mask is computed and `hits` is not
/// written; else all four lanes are, and the lanes of the mask are the hits.
template <bool with_hits = true>
RT_BVH_INLINE int intersect_block_sse(const triangle_block& b, const leaf_ray& r, const watertight_ray& w, float tmin,
                                      float tmax, block_hits& hits)
{
    const __m128 zero = _mm_setzero_ps();
    // corners translated to the origin and permuted: x (kx), y (ky), z (kz);
    // corner i's rows of triangle_block::v are 3 i + kx, 3 i + ky, 3 i + kz
    const float* x = b.v[w.kx];
    const float* y = b.v[w.ky];
    const float* z = b.v[w.kz];
    const __m128 ax = _mm_sub_ps(_mm_load_ps(x), r.px);
    const __m128 bx = _mm_sub_ps(_mm_load_ps(x + 12), r.px);
    const __m128 cx = _mm_sub_ps(_mm_load_ps(x + 24), r.px);
    const __m128 ay = _mm_sub_ps(_mm_load_ps(y), r.py);
    const __m128 by = _mm_sub_ps(_mm_load_ps(y + 12), r.py);
    const __m128 cy = _mm_sub_ps(_mm_load_ps(y + 24), r.py);
    const __m128 az = _mm_sub_ps(_mm_load_ps(z), r.pz);
    const __m128 bz = _mm_sub_ps(_mm_load_ps(z + 12), r.pz);
    const __m128 cz = _mm_sub_ps(_mm_load_ps(z + 24), r.pz);
    // sheared
    const __m128 Ax = _mm_sub_ps(ax, _mm_mul_ps(r.Sx, az));
    const __m128 Ay = _mm_sub_ps(ay, _mm_mul_ps(r.Sy, az));
    const __m128 Bx = _mm_sub_ps(bx, _mm_mul_ps(r.Sx, bz));
    const __m128 By = _mm_sub_ps(by, _mm_mul_ps(r.Sy, bz));
    const __m128 Cx = _mm_sub_ps(cx, _mm_mul_ps(r.Sx, cz));
    const __m128 Cy = _mm_sub_ps(cy, _mm_mul_ps(r.Sy, cz));
    // edge functions: first in float, each product rounded on its own, to
    // reject the lanes whose nonzero values have mixed signs (exact signs:
    // see intersect_watertight) and the unused and sphere lanes (NaN in row
    // 4, b.y); then, as intersect_watertight does for a possible hit, in
    // double for all four lanes. A NaN edge function from finite corners (an
    // overflow in float) is not rejected here: double decides it.
    {
        const __m128 U = _mm_sub_ps(rounded_product4(Cx, By), rounded_product4(Cy, Bx));
        const __m128 V = _mm_sub_ps(rounded_product4(Ax, Cy), rounded_product4(Ay, Cx));
        const __m128 W = _mm_sub_ps(rounded_product4(Bx, Ay), rounded_product4(By, Ax));
        const __m128 below = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(U, zero), _mm_cmplt_ps(V, zero)), _mm_cmplt_ps(W, zero));
        const __m128 above = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(U, zero), _mm_cmpgt_ps(V, zero)), _mm_cmpgt_ps(W, zero));
        const __m128 row4 = _mm_load_ps(b.v[4]);
        const __m128 out = _mm_or_ps(_mm_and_ps(below, above), _mm_cmpunord_ps(row4, row4));
        if (_mm_movemask_ps(out) == 15)
            return 0;
    }
    const wide4 Ax2 = widen(Ax), Ay2 = widen(Ay), Bx2 = widen(Bx), By2 = widen(By), Cx2 = widen(Cx), Cy2 = widen(Cy);
    const __m128 U = edge_function4(Cx2, By2, Cy2, Bx2);
    const __m128 V = edge_function4(Ax2, Cy2, Ay2, Cx2);
    const __m128 W = edge_function4(Bx2, Ay2, By2, Ax2);
    const __m128 negative =
        _mm_or_ps(_mm_or_ps(_mm_cmpnge_ps(U, zero), _mm_cmpnge_ps(V, zero)), _mm_cmpnge_ps(W, zero));
    const __m128 positive =
        _mm_or_ps(_mm_or_ps(_mm_cmpnle_ps(U, zero), _mm_cmpnle_ps(V, zero)), _mm_cmpnle_ps(W, zero));
    int mask = ~_mm_movemask_ps(_mm_and_ps(negative, positive)) & 15;
    if (mask == 0)
        return 0;
    // det, T and t as watertight_finish computes them; t in [tmin, tmax] (a
    // NaN fails both comparisons: unused and sphere lanes end here) and det != 0
    const __m128 det = _mm_add_ps(_mm_add_ps(U, V), W);
    const __m128 Az = _mm_mul_ps(r.Sz, az), Bz = _mm_mul_ps(r.Sz, bz), Cz = _mm_mul_ps(r.Sz, cz);
    const __m128 T = _mm_add_ps(_mm_add_ps(_mm_mul_ps(U, Az), _mm_mul_ps(V, Bz)), _mm_mul_ps(W, Cz));
    const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1.0f), det);
    const __m128 t = _mm_mul_ps(T, inv_det);
    const __m128 in_range = _mm_and_ps(_mm_and_ps(_mm_cmpge_ps(t, _mm_set1_ps(tmin)), _mm_cmple_ps(t, _mm_set1_ps(tmax))),
                                       _mm_cmpneq_ps(det, zero));
    mask &= _mm_movemask_ps(in_range);
    if (mask == 0)
        return 0;
    // the distance check, watertight_t_error<float> lane by lane, the same
    // operations in the same order (_mm_max_ps(a, b) is a > b ? a : b, as in
    // max_abs3; the absolute value clears the sign bit, as std::fabs)
    const __m128 sign = _mm_set1_ps(-0.0f);
    const __m128 max_x = max_abs3_sse(ax, bx, cx), max_y = max_abs3_sse(ay, by, cy), max_z = max_abs3_sse(az, bz, cz);
    const __m128 max_X = max_abs3_sse(Ax, Bx, Cx), max_Y = max_abs3_sse(Ay, By, Cy), max_Z = max_abs3_sse(Az, Bz, Cz);
    const __m128 max_E = max_abs3_sse(U, V, W);
    const __m128 gamma2 = _mm_set1_ps(gamma_in<float>(2)), gamma3 = _mm_set1_ps(gamma_in<float>(3));
    const __m128 gamma5 = _mm_set1_ps(gamma_in<float>(5));
    const __m128 delta_x = _mm_mul_ps(gamma5, _mm_add_ps(max_x, max_z));
    const __m128 delta_y = _mm_mul_ps(gamma5, _mm_add_ps(max_y, max_z));
    const __m128 delta_z = _mm_mul_ps(gamma3, max_Z);
    const __m128 delta_e = _mm_mul_ps(
        _mm_set1_ps(2.0f), _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(gamma2, max_X), max_Y), _mm_mul_ps(delta_y, max_X)),
                                      _mm_mul_ps(delta_x, max_Y)));
    const __m128 bound = _mm_mul_ps(
        _mm_mul_ps(_mm_set1_ps(3.0f), _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(gamma3, max_E), max_Z),
                                                            _mm_mul_ps(delta_e, max_Z)),
                                                 _mm_mul_ps(delta_z, max_E))),
        _mm_andnot_ps(sign, inv_det));
    const int beyond = _mm_movemask_ps(_mm_cmpgt_ps(t, bound));
    // the lanes within their bound get the second opinion in double (rare)
    for (int doubtful = mask & ~beyond, lane = 0; doubtful != 0; ++lane, doubtful >>= 1)
        if ((doubtful & 1) && !t_beyond_error_in_double(w, &b.v[0][lane], 4))
            mask &= ~(1 << lane);
    if (!with_hits || mask == 0)
        return mask;
    _mm_store_ps(hits.t, t);
    _mm_store_ps(hits.b0, _mm_mul_ps(U, inv_det));
    _mm_store_ps(hits.b1, _mm_mul_ps(V, inv_det));
    _mm_store_ps(hits.b2, _mm_mul_ps(W, inv_det));
    return mask;
}
#endif

/// The leaf test of bvh traversal: intersect_block_sse where SSE is there,
/// else intersect_block_scalar. Both give the same bits.
template <bool with_hits = true>
RT_BVH_INLINE int intersect_block(const triangle_block& b, const leaf_ray& r, const watertight_ray& w, real tmin,
                                  real tmax, block_hits& hits)
{
#if RT_BVH_SSE
    return intersect_block_sse<with_hits>(b, r, w, tmin, tmax, hits);
#else
    (void)r;
    return intersect_block_scalar(b, w, tmin, tmax, hits);
#endif
}

} // namespace RT_BVH_ABI
} // namespace detail
} // namespace rt

#endif // RT_BVH_LEAF_TEST_W8X / _W8 / _W4

#include "simd_end.hpp"
