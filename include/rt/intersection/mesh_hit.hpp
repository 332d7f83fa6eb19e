// mesh_hit.hpp - a ray against every triangle of one mesh, by the library's
// watertight test (watertight.hpp): the flat search inside a mesh that the
// scene's flat list (shape_hit.hpp) uses; the BVH (bvh.hpp) does the same
// work faster and returns the same hits.
//
//     rt::hit_record rec;
//     if (rt::hit_mesh(m, r, 0, rt::infinity, rec)) ... // rec.primitive: which triangle
#pragma once

#include <cstddef>

#include "../core/hit_record.hpp"
#include "../scene/mesh.hpp"
#include "../core/ray.hpp"
#include "../core/vec.hpp"
#include "watertight.hpp"

namespace rt {

namespace detail {

/// The nine corner coordinates of triangle i (a.x a.y a.z b.x ... c.z), as
/// intersect_watertight takes them.
inline void triangle_corners(const mesh& m, std::size_t i, real v[9])
{
    const index3& face = m.triangles[i];
    for (int k = 0; k < 3; ++k) {
        const vec3& p = m.positions[face[std::size_t(k)]];
        v[3 * k] = p.x;
        v[3 * k + 1] = p.y;
        v[3 * k + 2] = p.z;
    }
}

/// The watertight hit of triangle i of `m` in [tmin, tmax], the record
/// complete (the student's groups test one triangle at a time: groups.hpp).
inline bool hit_mesh_triangle(const mesh& m, std::size_t i, const ray& r, real tmin, real tmax, hit_record& rec)
{
    real v[9];
    triangle_corners(m, i, v);
    triangle_hit h;
    if (!intersect_watertight(make_watertight_ray(r), v, tmin, tmax, h))
        return false;
    const index3& face = m.triangles[i];
    fill_triangle_record(m.positions[face[0]], m.positions[face[1]], m.positions[face[2]], r, h, rec);
    complete_mesh_hit(m, i, rec);
    return true;
}

} // namespace detail

/// The closest hit in [tmin, tmax] over all triangles of `m`, by testing each in
/// turn (the BVH of accelerator.hpp does the same work faster). When two
/// triangles give the same t, the later one is kept, as the scene's flat list
/// does.
inline bool hit_mesh(const mesh& m, const ray& r, real tmin, real tmax, hit_record& rec)
{
    const watertight_ray w = make_watertight_ray(r);
    bool found = false;
    std::size_t best = 0;
    triangle_hit best_hit;
    real closest = tmax;
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
        real v[9];
        detail::triangle_corners(m, i, v);
        triangle_hit h;
        if (intersect_watertight(w, v, tmin, closest, h)) {
            found = true;
            best = i;
            best_hit = h;
            closest = h.t;
        }
    }
    if (!found)
        return false;
    const index3& face = m.triangles[best];
    fill_triangle_record(m.positions[face[0]], m.positions[face[1]], m.positions[face[2]], r, best_hit, rec);
    complete_mesh_hit(m, best, rec);
    return true;
}

} // namespace rt
