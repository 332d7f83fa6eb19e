// textbook_list.hpp - the scene's shapes tested by the student's own methods:
// spheres by the textbook quadratic (stage 03), triangles and a mesh's
// triangles by Moller-Trumbore (stage 04), all through the student's list
// (rt::closest_hit_list, stage 04). The stage-04 program renders with it, so
// its images show the student's code; the library's watertight BVH
// (stage::world) is the comparison.
#pragma once

#include <cstddef>
#include <variant>

#include <rt/intersection/hit_list.hpp>
#include <rt/scene/mesh.hpp>
#include <rt/intersection/sphere.hpp>
#include <rt/intersection/triangle.hpp>

namespace stage {

/// One shape by the textbook methods: the closest hit in [tmin, tmax].
inline bool hit_shape_textbook(const rt::shape& item, const rt::ray& r, rt::real tmin, rt::real tmax,
                               rt::hit_record& rec)
{
    if (const rt::sphere* ball = std::get_if<rt::sphere>(&item))
        return rt::hit_sphere_textbook(*ball, r, tmin, tmax, rec);
    if (const rt::triangle* tri = std::get_if<rt::triangle>(&item))
        return rt::hit_triangle_moller_trumbore(*tri, r, tmin, tmax, rec);
    // a mesh: each triangle in turn, each hit narrowing tmax, as the list does
    const rt::mesh& m = std::get<rt::mesh>(item);
    bool found = false;
    rt::real closest = tmax;
    for (std::size_t k = 0; k < m.triangles.size(); ++k) {
        const rt::index3& face = m.triangles[k];
        rt::triangle tri;
        tri.a = m.positions[face[0]];
        tri.b = m.positions[face[1]];
        tri.c = m.positions[face[2]];
        rt::hit_record candidate;
        if (rt::hit_triangle_moller_trumbore(tri, r, tmin, closest, candidate)) {
            found = true;
            closest = candidate.t;
            rec = candidate;
            rt::complete_mesh_hit(m, k, rec); // the mesh's material and interpolated normal
        }
    }
    return found;
}

/// The student's list over the scene, with the textbook methods: an
/// accelerator (closest_hit, any_hit) for recording and rendering.
struct textbook_list {
    const rt::scene* s;

    bool closest_hit(const rt::ray& r, rt::real tmin, rt::real tmax, rt::hit_record& rec) const
    {
        return rt::closest_hit_list(*s, r, tmin, tmax, rec, hit_shape_textbook);
    }
    bool any_hit(const rt::ray& r, rt::real tmin, rt::real tmax) const
    {
        rt::hit_record unused;
        return rt::closest_hit_list(*s, r, tmin, tmax, unused, hit_shape_textbook);
    }
};

} // namespace stage
