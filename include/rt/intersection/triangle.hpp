// triangle.hpp - the stage-04 exercise: a ray against a triangle by Moller-Trumbore.
//
// The triangle itself (struct triangle, triangle_hit, triangle_normal,
// fill_triangle_record) is in triangle_shape.hpp; the library's own method,
// the watertight test, in watertight.hpp. Only the stage-04 program and tests
// (and the benchmarks that compare the two methods) include this header.
//
// Both methods (1. below, 2. the watertight test in watertight.hpp) find t and the barycentric coordinates (b0, b1, b2) of the hit,
// b0 + b1 + b2 = 1, with the hit point b0 a + b1 b + b2 c. Both are two-sided:
// a ray hits the front (seen counter-clockwise) and the back alike, and
// front_face says which one it hit.
//
// 1. Moller-Trumbore (Moller, Trumbore, "Fast, Minimum Storage Ray/Triangle
//    Intersection", Journal of Graphics Tools 2(1), 1997, sec. 2): with the
//    edges e1 = b - a, e2 = c - a and Cramer's rule on p + t d = a + u e1 + v e2,
//        P = d x e2,  det = e1 . P,  T = p - a,  Q = T x e1,
//        u = (T . P) / det,  v = (d . Q) / det,  t = (e2 . Q) / det,
//    a hit when u >= 0, v >= 0, u + v <= 1 (b1 = u, b2 = v). This is the
//    stage-04 exercise. Each triangle tests its own u and v, so the two
//    triangles that share an edge compute that edge's test differently; a ray
//    aimed exactly at the edge can fail both and slip through the mesh (the
//    stage-04 tests count such leaks, docs/stages/04-triangle.md shows them).
#pragma once

#include <glm/geometric.hpp>

#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../scene/triangle_shape.hpp"
#include "../core/vec.hpp"

namespace rt {

/// Moller-Trumbore, as the 1997 paper gives it (see the top of this file):
/// the hit in [tmin, tmax], two-sided, with the record filled by
/// fill_triangle_record. Kept for teaching and for comparison; it leaks
/// through shared edges, which the watertight test does not.
inline bool hit_triangle_moller_trumbore(const triangle& tri, const ray& r, real tmin, real tmax,
                                         hit_record& rec)
{
    // RT_EXERCISE_BEGIN(stage04: Moller-Trumbore ray-triangle intersection)
    const vec3 e1 = tri.b - tri.a;
    const vec3 e2 = tri.c - tri.a;
    const vec3 P = glm::cross(r.direction, e2);
    const real det = glm::dot(e1, P);
    if (det == 0) // the ray is parallel to the triangle's plane
        return false;
    const real inv_det = 1 / det;
    const vec3 T = r.origin - tri.a;
    const real u = glm::dot(T, P) * inv_det;
    if (u < 0 || u > 1)
        return false;
    const vec3 Q = glm::cross(T, e1);
    const real v = glm::dot(r.direction, Q) * inv_det;
    if (v < 0 || u + v > 1)
        return false;
    const real t = glm::dot(e2, Q) * inv_det;
    if (t < tmin || t > tmax)
        return false;
    fill_triangle_record(tri.a, tri.b, tri.c, r, triangle_hit{t, 1 - u - v, u, v}, rec);
    rec.material = tri.material;
    return true;
    // RT_EXERCISE_END
}

} // namespace rt
