// intersect.hpp - the nearest hit of a ray in a whole scene (stage 04): both halves.
//
// Kept so that code including <rt/intersect.hpp> compiles; new code includes
// the half it uses:
//   - accelerator.hpp: rt::accelerator, the library's scene-level intersection
//     (flat list or BVH), what the shading, shadows and reflections use;
//   - hit_list.hpp: closest_hit_list, the stage-04 exercise (the loop over the
//     shapes), and any_hit_list;
//   - shape_hit.hpp: hit_shape, one shape by the robust methods.
// The library and the stage support libraries include accelerator.hpp only, so
// an edit to the exercise rebuilds only the stage-04 program and tests.
#pragma once

#include "accelerator.hpp"
#include "hit_list.hpp"
#include "ray.hpp" // rt::infinity
