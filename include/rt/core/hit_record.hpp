// hit_record.hpp - what a ray-surface intersection reports (stage 03 on).
//
// point_error is the box of rounding error around `point` that the exact
// surface point lies in (Physically Based Rendering, 3rd ed., sec. 3.9.4);
// spawn.hpp offsets new rays past it so they cannot hit the same surface again.
// The scene-level intersection (accelerator.hpp) fills it; 0 means "not known".
#pragma once

#include <cstdint>

#include "vec.hpp"

namespace rt {

struct hit_record {
    real t = 0;                ///< ray parameter of the hit: point = p + t d, up to rounding
    vec3 point{0};             ///< the hit point
    vec3 point_error{0};       ///< per axis, a bound on |point - the true surface point| (0: not known)
    vec3 geometric_normal{0};  ///< unit normal of the true surface, facing the incoming ray
    vec3 normal{0};            ///< unit shading normal (interpolated on meshes), facing the ray
    bool front_face = true;    ///< the ray hit the outside (against the outward normal)
    int material = -1;         ///< index into scene::materials; -1: the default material
    std::uint32_t shape = 0;   ///< index into scene::shapes
    std::uint32_t primitive = 0;  ///< triangle index inside a mesh, else 0
    real b1 = 0, b2 = 0;       ///< barycentric coordinates of b and c (triangles)
};

} // namespace rt
