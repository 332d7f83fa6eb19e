// textbook_groups.hpp - the student's groups (rt::build_groups and
// rt::closest_hit_groups, stage 04) over the scene's primitives, each tested
// by the student's own methods: spheres by the textbook quadratic (stage 03),
// triangles and a mesh's triangles by Moller-Trumbore (stage 04). The
// stage-04 program renders with it and times it against the student's list
// (textbook_list.hpp, the same methods, no groups).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <variant>

#include <rt/intersection/groups.hpp>
#include <rt/scene/mesh.hpp>
#include <rt/intersection/sphere.hpp>
#include <rt/intersection/triangle.hpp>

namespace stage {

/// One item (a sphere, a triangle, or a mesh's triangle) by the textbook
/// methods, the record complete with the item's shape and primitive.
inline bool hit_item_textbook(const rt::scene& s, const rt::group_item& item, const rt::ray& r, rt::real tmin,
                              rt::real tmax, rt::hit_record& rec)
{
    const rt::shape& target = s.shapes[item.shape];
    bool found = false;
    if (const rt::sphere* ball = std::get_if<rt::sphere>(&target)) {
        found = rt::hit_sphere_textbook(*ball, r, tmin, tmax, rec);
    } else if (const rt::triangle* tri = std::get_if<rt::triangle>(&target)) {
        found = rt::hit_triangle_moller_trumbore(*tri, r, tmin, tmax, rec);
    } else {
        const rt::mesh& m = std::get<rt::mesh>(target);
        const rt::index3& face = m.triangles[item.primitive];
        const rt::triangle corners{m.positions[face[0]], m.positions[face[1]], m.positions[face[2]], -1};
        found = rt::hit_triangle_moller_trumbore(corners, r, tmin, tmax, rec);
        if (found)
            rt::complete_mesh_hit(m, item.primitive, rec); // the mesh's material and interpolated normal
    }
    if (found) {
        rec.shape = item.shape;
        rec.primitive = item.primitive;
    }
    return found;
}

/// The student's groups over the scene, with the textbook methods: an
/// accelerator (closest_hit, any_hit) for rendering.
struct textbook_groups {
    const rt::scene* s;
    rt::groups g;

    textbook_groups(const rt::scene& scene, std::size_t leaf_size = 4)
        : s(&scene), g(rt::build_groups(rt::group_items(scene), leaf_size))
    {
    }

    bool closest_hit(const rt::ray& r, rt::real tmin, rt::real tmax, rt::hit_record& rec) const
    {
        auto hit_item = [this](std::uint32_t i, const rt::ray& ray, rt::real t0, rt::real t1, rt::hit_record& h) {
            return hit_item_textbook(*s, g.items[i], ray, t0, t1, h);
        };
        return rt::closest_hit_groups(g, r, tmin, tmax, rec, hit_item);
    }
    bool any_hit(const rt::ray& r, rt::real tmin, rt::real tmax) const
    {
        rt::hit_record unused;
        return closest_hit(r, tmin, tmax, unused);
    }
};

} // namespace stage
