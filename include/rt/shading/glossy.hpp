// glossy.hpp - glossy reflection: a blurred mirror (stage 10).
//
// A perfect mirror (stage 07) reflects each ray in one direction r. Brushed
// metal reflects a blurred image: distribution ray tracing (Cook, Porter,
// Carpenter 1984) sends each sample's reflected ray in a random direction near
// r, and the samples of a pixel average the blur. Fundamentals of Computer
// Graphics, 4th ed., sec. 13.4.4: with u, v a basis of the plane
// perpendicular to r, take a random point of the square of side a centred on
// the tip of r,
//     r' = r + (xi1 - 1/2) a u + (xi2 - 1/2) a v,
// and reflect along r' (normalised). a = 0 is the perfect mirror; the larger a,
// the blurrier. A direction that ends up below the surface is drawn again.
//
//     const rt::vec3 r2 = rt::glossy_direction(r, a, xi1, xi2);
//     const rt::vec3 dir = rt::mirror_direction(m, d, hit.normal, options); // what ray_color_glass reflects along
#pragma once

#include <cmath>

#include <glm/geometric.hpp>

#include "../core/config.hpp"
#include "../scene/material.hpp"
#include "raytracer.hpp"
#include "../scene/scene.hpp"
#include "shading.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The unit direction r + (xi1 - 1/2) a u + (xi2 - 1/2) a v, normalised, for
/// the unit mirror direction r, u and v any orthonormal pair perpendicular to
/// r (FCG 4th ed., sec. 13.4.4).
inline vec3 glossy_direction(const vec3& r, real a, real xi1, real xi2)
{
    // RT_EXERCISE_BEGIN(stage10: glossy reflection)
    // any unit vector not parallel to r gives the rest of the frame
    const vec3 helper = std::fabs(r.x) > real(0.9) ? vec3(0, 1, 0) : vec3(1, 0, 0);
    const vec3 u = glm::normalize(glm::cross(helper, r));
    const vec3 v = glm::cross(r, u);
    return glm::normalize(r + (xi1 - real(0.5)) * a * u + (xi2 - real(0.5)) * a * v);
    // RT_EXERCISE_END
}

/// The direction a mirror of material m reflects the ray direction d in, about
/// the unit normal n that faces the ray: reflect(d, n) (stage 07), or, for a
/// glossy mirror (m.glossy > 0) with options.random, glossy_direction about
/// the unit mirror direction; a perturbed direction below the surface is drawn
/// again, and after 8 tries the mirror direction is used.
inline vec3 mirror_direction(const material& m, const vec3& d, const vec3& n, const shading_options& options)
{
    const vec3 r = reflect(d, n);
    if (!(m.glossy > 0) || options.random == nullptr)
        return r;
    const vec3 unit = glm::normalize(r);
    for (int attempt = 0; attempt < 8; ++attempt) {
        const real xi1 = options.random->next_float(), xi2 = options.random->next_float();
        const vec3 g = glossy_direction(unit, m.glossy, xi1, xi2);
        if (glm::dot(g, n) > 0)
            return g;
    }
    return r;
}

/// True when some material of s is a glossy mirror: the scene needs stage 10's random numbers.
inline bool has_glossy(const scene& s)
{
    for (const material& m : s.materials)
        if (m.glossy > 0)
            return true;
    return s.default_material.glossy > 0;
}

} // namespace rt
