// triangle_shape.hpp - a triangle with corners a, b, c: the shape a scene holds,
// its normal and the hit record of a hit on it (stage 04).
//
// The two ways to intersect a ray with it are in their own headers:
// triangle.hpp holds the stage-04 exercise (Moller-Trumbore), watertight.hpp
// the library's method (the watertight test). The scene, the meshes, the
// loaders and the BVH include this header and watertight.hpp, never the
// exercise, so that editing the exercise rebuilds only what calls it.
//
// Both methods find t and the barycentric coordinates (b0, b1, b2) of the hit,
// b0 + b1 + b2 = 1, with the hit point b0 a + b1 b + b2 c. Both are two-sided:
// a ray hits the front (seen counter-clockwise) and the back alike, and
// front_face says which one it hit.
#pragma once

#include <cmath>
#include <type_traits>

#include <glm/geometric.hpp>

#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../core/rounding.hpp"
#include "../core/vec.hpp"

namespace rt {

struct triangle {
    vec3 a{0}, b{0}, c{0};  ///< corners, counter-clockwise seen from the front
    int material = -1;      ///< index into scene::materials; -1: the default material
};

/// A ray-triangle hit before a hit record is filled: the ray parameter and the
/// barycentric coordinates of the corners a, b, c (b0 + b1 + b2 = 1).
struct triangle_hit {
    real t = 0;
    real b0 = 0, b1 = 0, b2 = 0;
};

/// The unit normal n = (b - a) x (c - a) / |(b - a) x (c - a)| of the triangle
/// a, b, c (the front is the side the corners turn counter-clockwise on), or
/// the zero vector when the corners lie on one line. With rt::real = float it
/// is computed in double from the float corners and rounded once: in float,
/// the edges and the cross product of a long thin triangle lose most of their
/// digits (of 1000 triangles with coordinates 10^-8 ... 10^8, 361 had a float
/// normal more than 1e-5 rad off, one 0.0218 rad (issue 19), enough to offset
/// a spawned ray to the wrong side: tests/library_reintersect.cpp). In double
/// the difference of two floats is exact when their exponents are at most 29
/// apart (53 = 24 + 29 bits), else off by at most 2^-53 relative, and each
/// product and difference of the cross product adds one rounding of 2^-53
/// (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed., sec.
/// 2.2): the direction is right to about an ulp of float unless a component
/// cancels by more than 2^29. Every path that fills a hit record
/// (hit_triangle, meshes, the flat list and the BVH's SIMD leaves, through
/// fill_triangle_record) calls it with the same corners, so they agree bit
/// for bit.
inline vec3 triangle_normal(const vec3& a, const vec3& b, const vec3& c)
{
    using wide = std::conditional_t<std::is_same_v<real, float>, double, real>;
    const wide e1[3] = {wide(b.x) - wide(a.x), wide(b.y) - wide(a.y), wide(b.z) - wide(a.z)};
    const wide e2[3] = {wide(c.x) - wide(a.x), wide(c.y) - wide(a.y), wide(c.z) - wide(a.z)};
    const wide n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    // (compared by hand: std::fmax is a call into the maths library, and the
    // components are never NaN for finite corners)
    const wide ax = std::fabs(n[0]), ay = std::fabs(n[1]), az = std::fabs(n[2]);
    if constexpr (std::is_same_v<real, float>) {
        // no normal when all three are zero, or one is not finite: tested on
        // their sum (finite exactly when all three are, see below), not on the
        // largest, whose choice is a branch that a hit's random orientation
        // mispredicts (docs/performance.md, experiment 6)
        const wide sum = ax + ay + az;
        if (!(sum > 0) || !std::isfinite(sum))
            return vec3(0);
        // From float corners no square overflows or underflows in double: a
        // nonzero component is a multiple of 2^-298 (a difference of products
        // of differences of floats) below 2^259, so its square lies between
        // 2^-596 and 2^518. So no scaling, and one division: this runs for
        // every hit.
        const wide inv_length = 1 / std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        return vec3(real(n[0] * inv_length), real(n[1] * inv_length), real(n[2] * inv_length));
    } else {
        const wide largest = ax > ay ? (ax > az ? ax : az) : (ay > az ? ay : az);
        if (!(largest > 0) || !std::isfinite(largest))
            return vec3(0);
        // scaled by the largest component first, so neither the squares
        // overflow nor they underflow for tiny triangles
        const wide x = n[0] / largest, y = n[1] / largest, z = n[2] / largest;
        const wide length = std::sqrt(x * x + y * y + z * z);
        return vec3(real(x / length), real(y / length), real(z / length));
    }
}

/// Fills `rec` for a hit on the triangle a, b, c described by `h`:
///  - point = b0 a + b1 b + b2 c, and point_error, the bound on its rounding
///    error gamma_7 (|b0 a| + |b1 b| + |b2 c|) (PBR 3rd ed., sec. 3.9.4);
///  - the geometric normal triangle_normal(a, b, c); front_face = d . n < 0;
///    the stored normals are turned to face the incoming ray. A triangle whose
///    corners lie on one line has no normal (the loaders refuse it); if one
///    is hit all the same, the normal is -d / |d|, never NaN;
///  - t, b1, b2, primitive 0. The material is left to the caller.
/// `normal` is triangle_normal(a, b, c), given by a caller that stored it (a
/// BVH computes it once per triangle when it is built: the double square root
/// and division were most of a record's cost).
inline void fill_triangle_record(const vec3& a, const vec3& b, const vec3& c, const vec3& normal, const ray& r,
                                 const triangle_hit& h, hit_record& rec)
{
    rec.t = h.t;
    rec.point = h.b0 * a + h.b1 * b + h.b2 * c;
    // |x| as std::fabs, one instruction (glm::abs compares and selects)
    auto abs3 = [](const vec3& v) { return vec3(std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)); };
    rec.point_error = gamma_n(7) * (abs3(h.b0 * a) + abs3(h.b1 * b) + abs3(h.b2 * c));
    vec3 n = normal;
    if (n == vec3(0))
        n = -glm::normalize(r.direction);
    rec.front_face = glm::dot(r.direction, n) < 0;
    // n or -n by a factor of +-1 (exact), not a branch: from inside a model
    // the side a ray meets is a coin toss
    rec.geometric_normal = n * (real(2) * real(rec.front_face) - real(1));
    rec.normal = rec.geometric_normal;
    rec.b1 = h.b1;
    rec.b2 = h.b2;
    rec.primitive = 0;
}

/// The same, with the normal computed here.
inline void fill_triangle_record(const vec3& a, const vec3& b, const vec3& c, const ray& r,
                                 const triangle_hit& h, hit_record& rec)
{
    fill_triangle_record(a, b, c, triangle_normal(a, b, c), r, h, rec);
}

} // namespace rt
