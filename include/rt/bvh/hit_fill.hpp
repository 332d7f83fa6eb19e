// bvh/hit_fill.hpp - the hit record of a triangle the BVH found, filled from
// its leaf block in SSE.
//
//     // h: the closest hit of bvh::closest (packed.hpp), its corners in the block
//     rt::detail::fill_triangle_record_strided(h.corners, h.stride, *h.normal, r, hit, rec);
//
// The record is fill_triangle_record's (triangle_shape.hpp): the point
// b0 a + b1 b + b2 c, its error bound gamma_7 (|b0 a| + |b1 b| + |b2 c|), the
// stored normal turned to face the ray. Each x, y, z triple is one SSE
// register here, where the scalar code spent about a hundred instructions on
// three lanes at a time (docs/performance.md, experiment 6). The same
// operations in the same order, so the same bits: the tests compare the
// BVH's records with the flat list's, field for field.
#pragma once

#include "../core/config.hpp"
#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../core/rounding.hpp"
#include "../scene/triangle_shape.hpp"
#include "../core/vec.hpp"

#include "simd_begin.hpp" // RT_BVH_SSE, RT_BVH_INLINE and the intrinsics, until simd_end.hpp

namespace rt {
namespace detail {
inline namespace RT_BVH_ABI { // this width's fast path (bvh/abi_begin.hpp)

#if RT_BVH_SSE
/// v[0], v[k], v[2 k] in lanes x, y, z (0 in the fourth).
inline __m128 load_xyz(const float* v, int k)
{
    return _mm_setr_ps(v[0], v[k], v[2 * k], 0.0f);
}

/// Lanes x, y, z of `p` to out[0 .. 2].
inline void store_xyz(float* out, __m128 p)
{
    _mm_storel_pi(reinterpret_cast<__m64*>(out), p);
    _mm_store_ss(out + 2, _mm_movehl_ps(p, p));
}
#endif

/// fill_triangle_record(a, b, c, normal, r, h, rec) for corners stored k
/// values apart: v[k j] is coordinate j of a, b, c in turn (j = 0 ... 8), as
/// a leaf block holds them (k = 4) or a packed primitive (k = 1). `normal`
/// is triangle_normal(a, b, c).
RT_BVH_INLINE void fill_triangle_record_strided(const real* v, int k, const vec3& normal, const ray& r,
                                                const triangle_hit& h, hit_record& rec)
{
#if RT_BVH_SSE
    const __m128 pa = _mm_mul_ps(_mm_set1_ps(h.b0), load_xyz(v, k));
    const __m128 pb = _mm_mul_ps(_mm_set1_ps(h.b1), load_xyz(v + 3 * k, k));
    const __m128 pc = _mm_mul_ps(_mm_set1_ps(h.b2), load_xyz(v + 6 * k, k));
    rec.t = h.t;
    store_xyz(&rec.point.x, _mm_add_ps(_mm_add_ps(pa, pb), pc));
    // |x| clears the sign bit, as std::fabs does
    const __m128 magnitude = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 sum =
        _mm_add_ps(_mm_add_ps(_mm_and_ps(magnitude, pa), _mm_and_ps(magnitude, pb)), _mm_and_ps(magnitude, pc));
    store_xyz(&rec.point_error.x, _mm_mul_ps(_mm_set1_ps(gamma_n(7)), sum));
    __m128 n = load_xyz(&normal.x, 1);
    if ((_mm_movemask_ps(_mm_cmpeq_ps(n, _mm_setzero_ps())) & 7) == 7) { // no normal (never stored): rare
        const vec3 away = -glm::normalize(r.direction);
        n = load_xyz(&away.x, 1);
    }
    // d . n added as glm::dot adds, (x + y) + z
    const __m128 p = _mm_mul_ps(load_xyz(&r.direction.x, 1), n);
    const float d_dot_n = _mm_cvtss_f32(_mm_add_ss(_mm_add_ss(p, _mm_shuffle_ps(p, p, 1)), _mm_movehl_ps(p, p)));
    rec.front_face = d_dot_n < 0;
    // n times +1 or -1, a select rather than a branch (from inside a model
    // the side a ray meets is a coin toss)
    const __m128 facing = _mm_mul_ps(n, _mm_set1_ps(rec.front_face ? 1.0f : -1.0f));
    store_xyz(&rec.geometric_normal.x, facing);
    store_xyz(&rec.normal.x, facing);
    rec.b1 = h.b1;
    rec.b2 = h.b2;
    rec.primitive = 0;
#else
    const vec3 a(v[0], v[k], v[2 * k]), b(v[3 * k], v[4 * k], v[5 * k]), c(v[6 * k], v[7 * k], v[8 * k]);
    fill_triangle_record(a, b, c, normal, r, h, rec);
#endif
}

} // namespace RT_BVH_ABI
} // namespace detail
} // namespace rt

#include "simd_end.hpp"
