// watertight.hpp - the library's ray-triangle intersection: the watertight test (stage 04).
//
// The triangle is in triangle_shape.hpp; the stage-04 exercise, Moller-Trumbore,
// in triangle.hpp. This is the method the library uses (hit_triangle, meshes,
// the flat list and the BVH's leaves).
//
// Both methods (1. Moller-Trumbore in triangle.hpp, 2. below) find t and the barycentric coordinates (b0, b1, b2) of the hit,
// b0 + b1 + b2 = 1, with the hit point b0 a + b1 b + b2 c. Both are two-sided:
// a ray hits the front (seen counter-clockwise) and the back alike, and
// front_face says which one it hit.
//
// 2. Watertight (Woop, Benthin, Wald, "Watertight Ray/Triangle Intersection",
//    Journal of Computer Graphics Techniques 2(1), 2013, sec. 3 and fig. 4 to 6):
//    translate the corners to the ray origin, permute the axes so that the
//    largest component of d is z, shear so that the ray becomes the +z axis:
//        kz = argmax |d_k|, kx = kz + 1, ky = kx + 1 (mod 3), swap kx, ky if d_kz < 0
//        Sx = d_kx / d_kz,  Sy = d_ky / d_kz,  Sz = 1 / d_kz
//        A = a - p, Ax = A_kx - Sx A_kz, Ay = A_ky - Sy A_kz (and B, C alike)
//    then the 2D edge functions of the sheared triangle at the origin,
//        U = Cx By - Cy Bx,  V = Ax Cy - Ay Cx,  W = Bx Ay - By Ax,
//    are the scaled barycentrics of a, b, c. The ray hits when U, V, W do not
//    have mixed signs; det = U + V + W, T = U Sz A_kz + V Sz B_kz + W Sz C_kz,
//    t = T / det. A shared edge is computed from the same two sheared corners
//    in both of its triangles, so the two results are exact negatives of each
//    other and no ray can pass between them; when an edge function rounds to
//    exactly 0 the paper recomputes all three in double, so a ray through an
//    edge or a vertex is decided by the sign of the exact value. rt rejects
//    in float (each product rounded on its own, detail::rounded_product: a
//    compiler allowed to fuse a b - c d into one multiply-add would round the
//    two triangles of an edge differently and let rays through) and
//    recomputes in double every triangle that may be hit, whose t then comes
//    from the exact edge functions rounded once.
//    This is the library's default (hit_triangle, meshes, the BVH).
//
//    The watertight test also refuses a t that is not certainly positive given
//    the rounding error of the computation (Physically Based Rendering, 3rd
//    ed., sec. 3.9.6): a ray that starts on the triangle, such as a ray spawned
//    from a hit on it, cannot hit it again at a tiny t. That bound is loose for
//    slivers, so a t inside it gets a second opinion in double before it is
//    refused (detail::t_beyond_error_in_double).
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>

#include <glm/common.hpp>

#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../core/rounding.hpp"
#include "../scene/triangle_shape.hpp"
#include "../core/vec.hpp"

namespace rt {

/// What the watertight test computes once per ray (Woop et al. 2013, sec. 3):
/// the origin p, the axis permutation kx, ky, kz and the shear Sx, Sy, Sz; the
/// direction d is kept for the double-precision check of a tiny t (see
/// detail::t_beyond_error_in_double). Precondition: d is not the zero vector.
struct watertight_ray {
    real p[3] = {0, 0, 0};
    real d[3] = {0, 0, 1};
    int kx = 0, ky = 1, kz = 2;
    real Sx = 0, Sy = 0, Sz = 1;
};

inline watertight_ray make_watertight_ray(const ray& r)
{
    watertight_ray w;
    const real d[3] = {r.direction.x, r.direction.y, r.direction.z};
    w.p[0] = r.origin.x;
    w.p[1] = r.origin.y;
    w.p[2] = r.origin.z;
    w.d[0] = d[0];
    w.d[1] = d[1];
    w.d[2] = d[2];
    // kz = argmax |d_k| (the first of equals), then kx, ky, swapped where
    // d_kz < 0 to keep the winding, so front_face stays meaningful. Looked up
    // rather than branched on: a tracer's rays point every way, and each of
    // these branches would be a coin toss for the predictor.
    const real mx = std::fabs(d[0]), my = std::fabs(d[1]), mz = std::fabs(d[2]);
    static constexpr signed char largest[8] = {2, 2, 2, 0, 1, 2, 1, 0}; // by (mx>=my) | (mx>=mz)<<1 | (my>=mz)<<2
    w.kz = largest[int(mx >= my) | int(mx >= mz) << 1 | int(my >= mz) << 2];
    static constexpr signed char across[3][2][2] = {{{1, 2}, {2, 1}}, {{2, 0}, {0, 2}}, {{0, 1}, {1, 0}}}; // [kz][d_kz < 0]: kx, ky
    const int negative = d[w.kz] < 0 ? 1 : 0;
    w.kx = across[w.kz][negative][0];
    w.ky = across[w.kz][negative][1];
    w.Sx = d[w.kx] / d[w.kz];
    w.Sy = d[w.ky] / d[w.kz];
    w.Sz = 1 / d[w.kz];
    return w;
}

namespace detail {

/// gamma_n (rounding.hpp) in the floating-point type F: the same bound for a
/// computation carried out in double when rt::real is float.
template <class F>
constexpr F gamma_in(int n)
{
    constexpr F u = std::numeric_limits<F>::epsilon() / 2;
    return (F(n) * u) / (1 - F(n) * u);
}

/// a b rounded to F, kept apart from whatever uses it: a compiler allowed to
/// contract (GCC by default wherever the target has FMA, every ARM64 target
/// among them) would otherwise fuse a b - c d into fma(a, b, -c d), and the
/// two triangles of an edge, which compute a b - c d and c d - a b, would then
/// round differently and let rays through (library_watertight's case "a fused
/// multiply-add in the edge functions lets rays through shared edges" counts
/// them; docs/stages/04-going-further.md quotes the count).
/// The empty asm statement claims to change the product, so nothing can be
/// fused across it, and costs no instruction; MSVC 2022 does not contract
/// unless asked (/fp:contract), and an older MSVC or another compiler gets a
/// volatile copy.
template <class F>
inline F rounded_product(F a, F b)
{
    F p = a * b;
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || (defined(__i386__) && defined(__SSE2__)))
    if constexpr (std::is_same_v<F, float> || std::is_same_v<F, double>)
        __asm__("" : "+x"(p));
#elif (defined(__GNUC__) || defined(__clang__)) && defined(__aarch64__)
    __asm__("" : "+w"(p));
#elif defined(__GNUC__) || defined(__clang__)
    __asm__("" : "+m"(p));
#elif !defined(_MSC_VER) || _MSC_VER < 1930
    const volatile F kept = p;
    p = kept;
#endif
    return p;
}

/// The largest of |x|, |y|, |z|.
template <class F>
F max_abs3(F x, F y, F z)
{
    x = std::fabs(x);
    y = std::fabs(y);
    z = std::fabs(z);
    const F m = x > y ? x : y;
    return m > z ? m : z;
}

/// PBR 3rd ed., sec. 3.9.6: a bound on the rounding error of the t computed by
/// the watertight test in the type F, so that t <= bound means "possibly at or
/// behind the origin". x, y, z are the corners translated to the ray origin and
/// permuted; X, Y the sheared coordinates (X = x - Sx z, with |Sx|, |Sy| <= 1
/// because kz is the largest axis of d); Z the scaled ones (Sz z); U, V, W the
/// edge functions.
template <class F>
F watertight_t_error(const F x[3], const F y[3], const F z[3], const F X[3], const F Y[3], const F Z[3], F U, F V,
                     F W, F det)
{
    const F max_x = max_abs3(x[0], x[1], x[2]);
    const F max_y = max_abs3(y[0], y[1], y[2]);
    const F max_z = max_abs3(z[0], z[1], z[2]);
    const F max_X = max_abs3(X[0], X[1], X[2]);
    const F max_Y = max_abs3(Y[0], Y[1], Y[2]);
    const F max_Z = max_abs3(Z[0], Z[1], Z[2]);
    const F max_E = max_abs3(U, V, W);
    const F delta_x = gamma_in<F>(5) * (max_x + max_z);
    const F delta_y = gamma_in<F>(5) * (max_y + max_z);
    const F delta_z = gamma_in<F>(3) * max_Z;
    const F delta_e = 2 * (gamma_in<F>(2) * max_X * max_Y + delta_y * max_X + delta_x * max_Y);
    return 3 * (gamma_in<F>(3) * max_E * max_Z + delta_e * max_Z + delta_z * max_E) * std::fabs(1 / det);
}

/// The sliver case of the distance check. The bound of watertight_t_error
/// grows with the corners' distances over |det|, and |det| (twice the area of
/// the sheared triangle) is tiny for a sliver: on Sponza's slivers the float
/// bound exceeded the hit's own t, and light leaked through shadows (the case:
/// docs/performance.md, experiment 6). When the float t is within its bound, the whole test
/// (translation, shear, edge functions, det, T) is redone in double from the
/// float corners and ray, with the bound of the same formula in double, 2^29
/// times smaller: a t that is truly positive by more than that is accepted. A
/// ray that starts on the triangle, or behind it as a ray spawned from a hit
/// does (spawn_ray, offset_past_error_bounds), has an exact t <= 0, and the double
/// bound still refuses it. `v` holds the corners: coordinate j (a.x a.y a.z
/// b.x ...) at v[j * stride].
inline bool t_beyond_error_in_double(const watertight_ray& w, const real* v, int stride)
{
    const int kx = w.kx, ky = w.ky, kz = w.kz;
    const double Sz = 1 / double(w.d[kz]);
    const double Sx = double(w.d[kx]) * Sz, Sy = double(w.d[ky]) * Sz;
    double x[3], y[3], z[3], X[3], Y[3], Z[3];
    for (int i = 0; i < 3; ++i) {
        x[i] = double(v[(3 * i + kx) * stride]) - double(w.p[kx]);
        y[i] = double(v[(3 * i + ky) * stride]) - double(w.p[ky]);
        z[i] = double(v[(3 * i + kz) * stride]) - double(w.p[kz]);
        X[i] = x[i] - Sx * z[i];
        Y[i] = y[i] - Sy * z[i];
        Z[i] = Sz * z[i];
    }
    const double U = X[2] * Y[1] - Y[2] * X[1];
    const double V = X[0] * Y[2] - Y[0] * X[2];
    const double W = X[1] * Y[0] - Y[1] * X[0];
    const double det = U + V + W;
    if (det == 0)
        return false;
    const double t = (U * Z[0] + V * Z[1] + W * Z[2]) / det;
    return t > watertight_t_error<double>(x, y, z, X, Y, Z, U, V, W, det);
}

/// The watertight test's state after the edge functions: the corners
/// translated to the ray origin and permuted (x, y, z: kx, ky, kz), sheared
/// (X, Y) and the edge functions U, V, W. The scalar test fills it and hands
/// it to watertight_finish. The SIMD leaf test (bvh/leaf_test.hpp) does not
/// use it: it repeats the same arithmetic in the same order, four lanes at a
/// time, so both decide every hit with the same bits (library_watertight.cpp
/// compares them).
struct sheared_triangle {
    real x[3], y[3], z[3];
    real X[3], Y[3];
    real U, V, W;
};

/// From the edge functions to the hit (Woop et al. 2013, fig. 6): det, T and
/// t, the range [tmin, tmax], and the distance check of PBR sec. 3.9.6 with
/// its double-precision second opinion (t_beyond_error_in_double; `v` and
/// `stride` give it the corners). Precondition: U, V, W have no mixed signs.
inline bool watertight_finish(const watertight_ray& w, const sheared_triangle& s, const real* v, int stride,
                              real tmin, real tmax, triangle_hit& hit)
{
    const real det = s.U + s.V + s.W;
    if (det == 0) // the ray lies in the triangle's plane, or the triangle has no area
        return false;
    const real Z[3] = {w.Sz * s.z[0], w.Sz * s.z[1], w.Sz * s.z[2]};
    const real T = s.U * Z[0] + s.V * Z[1] + s.W * Z[2];
    const real inv_det = 1 / det;
    const real t = T * inv_det;
    if (!(t >= tmin && t <= tmax)) // also refuses NaN
        return false;
    // the conservative check of PBR 3rd ed., sec. 3.9.6 (see watertight_t_error),
    // and for float a second opinion in double when it refuses
    if (t <= watertight_t_error<real>(s.x, s.y, s.z, s.X, s.Y, Z, s.U, s.V, s.W, det)) {
        if constexpr (!std::is_same_v<real, float>)
            return false;
        else if (!t_beyond_error_in_double(w, v, stride))
            return false;
    }
    hit.t = t;
    hit.b0 = s.U * inv_det;
    hit.b1 = s.V * inv_det;
    hit.b2 = s.W * inv_det;
    return true;
}

} // namespace detail

/// The watertight test (see the top of this file) of the ray `w` against the
/// triangle whose corners a, b, c are the nine numbers v[0..8] (a.x a.y a.z
/// b.x ...). On a hit with t in [tmin, tmax] fills `hit` and returns true.
/// The result depends only on the ray and the corners, never on the order in
/// which triangles are tested: the flat list and the BVH agree exactly.
inline bool intersect_watertight(const watertight_ray& w, const real* v, real tmin, real tmax, triangle_hit& hit)
{
    const int kx = w.kx, ky = w.ky, kz = w.kz;
    // A, B, C translated to the ray origin, permuted and sheared
    detail::sheared_triangle s;
    for (int i = 0; i < 3; ++i) {
        s.x[i] = v[3 * i + kx] - w.p[kx];
        s.y[i] = v[3 * i + ky] - w.p[ky];
        s.z[i] = v[3 * i + kz] - w.p[kz];
        s.X[i] = s.x[i] - w.Sx * s.z[i];
        s.Y[i] = s.y[i] - w.Sy * s.z[i];
    }
    const real Ax = s.X[0], Ay = s.Y[0], Bx = s.X[1], By = s.Y[1], Cx = s.X[2], Cy = s.Y[2];

    // scaled barycentric coordinates: the edge functions, first in float with
    // each product rounded on its own (see detail::rounded_product). Rounding
    // is monotonic, so fl(a b) - fl(c d) has the sign of a b - c d or is 0:
    // two nonzero values of opposite signs are a miss, whatever the rest.
    using detail::rounded_product;
    real U = rounded_product(Cx, By) - rounded_product(Cy, Bx);
    real V = rounded_product(Ax, Cy) - rounded_product(Ay, Cx);
    if ((U < 0 && V > 0) || (U > 0 && V < 0))
        return false;
    real W = rounded_product(Bx, Ay) - rounded_product(By, Ax);
    if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0))
        return false;
    if constexpr (std::is_same_v<real, float>) {
        // A possible hit: the three again in double, where a product of two
        // floats is exact, so each is the exact value rounded once: the
        // paper's fallback for a 0 (which may be a rounded nonzero value),
        // done for every triangle that gets this far, because t and the
        // barycentrics are computed from these values and float's are less
        // accurate (on a sliver, a t of 2e-4 for a true 1e-6: a ray leaving
        // the triangle hit it again beyond a tmin of 1e-4).
        U = real(double(Cx) * double(By) - double(Cy) * double(Bx));
        V = real(double(Ax) * double(Cy) - double(Ay) * double(Cx));
        W = real(double(Bx) * double(Ay) - double(By) * double(Ax));
        if ((U < 0 || V < 0 || W < 0) && (U > 0 || V > 0 || W > 0))
            return false;
    }
    // (rt::real = double: nothing wider to fall back to; a 0 is then seen by
    // both triangles of the edge alike, and the ray counts as on the edge)
    s.U = U;
    s.V = V;
    s.W = W;
    return detail::watertight_finish(w, s, v, 1, tmin, tmax, hit);
}

/// The library's default ray-triangle intersection: the watertight test, with
/// the record filled by fill_triangle_record and the triangle's material.
inline bool hit_triangle(const triangle& tri, const ray& r, real tmin, real tmax, hit_record& rec)
{
    const real corners[9] = {tri.a.x, tri.a.y, tri.a.z, tri.b.x, tri.b.y, tri.b.z, tri.c.x, tri.c.y, tri.c.z};
    triangle_hit h;
    if (!intersect_watertight(make_watertight_ray(r), corners, tmin, tmax, h))
        return false;
    fill_triangle_record(tri.a, tri.b, tri.c, r, h, rec);
    rec.material = tri.material;
    return true;
}

} // namespace rt
