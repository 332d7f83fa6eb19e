// hit_list.hpp - the stage-04 exercise: the nearest hit of a ray in a whole
// scene by a loop over its shapes.
//
// The course's group: "loop over all objects, keep the closest hit". That loop
// is closest_hit_list, the stage-04 exercise, written for reading; any_hit_list
// is the same loop for shadow rays. The library (shading, shadows,
// reflections) uses rt::accelerator (accelerator.hpp) instead, which returns
// exactly the same hits faster; accelerator.hpp does not include this header,
// so editing the exercise rebuilds only the stage-04 program and tests.
//
// Closest means: the smallest t in [tmin, tmax]; at an equal t, the later
// primitive in scene order (shapes in file order, a mesh's triangles in its
// order), which is what the list loop does when it passes the closest t so far
// as tmax. The list, the flat accelerator and the BVH all follow this rule and
// all use the robust methods (rt::hit_sphere, the watertight triangle test), so
// they agree hit for hit.
//
// Every hit record is complete: t, point and its rounding error (for
// spawn_ray), geometric and shading normals facing the ray, front_face,
// material, shape, primitive, barycentrics. A sphere's hit point and normal
// are computed again from the ray relative to the centre, in a wider type
// (refine_sphere_hit), so the normal's direction does not depend on how far
// the ray came from.
#pragma once

#include <cstddef>
#include <cstdint>

#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../scene/scene.hpp"
#include "shape_hit.hpp"
#include "../core/vec.hpp"

namespace rt {

/// How the list tests one shape: its closest hit in [tmin, tmax], the record
/// filled but for rec.shape. hit_shape (the robust methods) by default; the
/// stage-04 program passes the textbook methods (stages 03 and 04) instead.
using shape_hit_function = bool (*)(const shape& item, const ray& r, real tmin, real tmax, hit_record& rec);

/// The course's group: loop over all the shapes of the scene, testing each
/// with `hit`, and keep the closest hit in [tmin, tmax]; rec.shape is the
/// index of the shape hit. At an equal t the later shape wins.
inline bool closest_hit_list(const scene& s, const ray& r, real tmin, real tmax, hit_record& rec,
                             shape_hit_function hit = hit_shape)
{
    // RT_EXERCISE_BEGIN(stage04: closest hit over the list of shapes)
    bool hit_anything = false;
    real closest = tmax;
    hit_record candidate;
    for (std::size_t i = 0; i < s.shapes.size(); ++i) {
        if (hit(s.shapes[i], r, tmin, closest, candidate)) {
            hit_anything = true;
            closest = candidate.t;
            rec = candidate;
            rec.shape = std::uint32_t(i);
        }
    }
    return hit_anything;
    // RT_EXERCISE_END
}

/// Whether any shape of the scene is hit in [tmin, tmax] (the list, for shadow rays).
inline bool any_hit_list(const scene& s, const ray& r, real tmin, real tmax)
{
    hit_record unused;
    for (const shape& item : s.shapes)
        if (hit_shape(item, r, tmin, tmax, unused))
            return true;
    return false;
}

} // namespace rt
