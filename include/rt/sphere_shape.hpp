// sphere_shape.hpp - the sphere a scene holds: centre c, radius R, material.
//
// Only the data: the intersection lives apart (sphere.hpp, the stage-03
// exercise; sphere_stable.hpp, the library's method), so that the scene, its
// loader and the BVH never include an exercise and an edit to one rebuilds
// only what uses it.
#pragma once

#include "vec.hpp"

namespace rt {

struct sphere {
    vec3 center{0};     ///< c
    real radius = 1;    ///< R
    int material = -1;  ///< index into scene::materials; -1: the default material
};

} // namespace rt
