// dielectric.hpp - the color seen along one ray, with glass (stage 09).
//
// Stage 07's ray_color (raytracer.hpp), with one more kind of surface: a
// dielectric (material::ior > 0) splits a ray in two, a reflected and a
// refracted one, weighted by the Fresnel reflectance R (Schlick's
// approximation), and what travelled inside it loses exp(-a s) (Beer's law).
// Fundamentals of Computer Graphics (Shirley, Marschner), 4th ed., sec. 13.1:
//     color = k (R raycolor(p, r) + (1 - R) raycolor(p, t))
//     r = reflect(d, n),  t = refract(d, n, eta, eta_t)  (refraction.hpp)
//     k = 1 entering, exp(-a s) leaving (s = t |d| the distance travelled inside)
// and only k raycolor(p, r) when refract finds none (total internal
// reflection). The outside is air (index 1); a dielectric holds no other shape.
//
//     const rt::accelerator accel(s);
//     rt::color L = rt::ray_color_glass(s, accel, camera_ray);
#pragma once

#include <limits>

#include <glm/geometric.hpp>

#include "glossy.hpp"
#include "../core/hit_record.hpp"
#include "../scene/material.hpp"
#include "../core/ray.hpp"
#include "raytracer.hpp"
#include "refraction.hpp"
#include "../scene/scene.hpp"
#include "shading.hpp"
#include "shadows.hpp"
#include "../intersection/spawn.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The color seen along ray r in scene s, as rt::ray_color (stage 07) sees it,
/// and through dielectrics: at a dielectric hit (material::ior > 0), while
/// depth < s.max_depth, add R times the color in the mirror direction and
/// 1 - R times the color in the refracted direction (only the mirror one on
/// total internal reflection), R = schlick_reflectance; a ray that hits a
/// dielectric from the inside (hit.front_face false) brings back
/// beer_attenuation(a, t |d|) of all it sees there. Mirrors and the recursion
/// trace with this function, so a mirror shows glass as glass; a mirror
/// reflects along mirror_direction (glossy.hpp), which is reflect unless the
/// material is glossy and `options` has random numbers (stage 10).
template <class Accelerator>
color ray_color_glass(const scene& s, const Accelerator& accel, const ray& r, int depth = 0,
                      const shading_options& options = {})
{
    // RT_EXERCISE_BEGIN(stage09: ray color with glass; repeats stage07)
    // Hint: start from your stage 07 ray_color and call ray_color_glass where it
    //   called itself, and let a mirror reflect along mirror_direction(m, r.direction,
    //   hit.normal, options) (glossy.hpp: reflect, blurred in stage 10); then add the
    //   dielectric's two rays (docs/stages/09-refraction.md).
    hit_record hit;
    if (!accel.closest_hit(r, real(0), std::numeric_limits<real>::infinity(), hit))
        return s.background;
    color L = direct_lighting(
        s, hit, r.direction, [&](const light_sample& sample) { return light_visible(accel, hit, sample); }, options);
    const material& m = s.material_of(hit.material);
    const auto trace = [&](const vec3& direction) {
        return ray_color_glass(s, accel, spawn_ray(hit, direction), depth + 1, options);
    };
    if (!is_dielectric(m)) { // stage 07's mirror (glossy in stage 10: mirror_direction, glossy.hpp)
        if ((m.km.r > 0 || m.km.g > 0 || m.km.b > 0) && depth < s.max_depth)
            L += m.km * trace(mirror_direction(m, r.direction, hit.normal, options));
        return L;
    }
    if (depth < s.max_depth) {
        // hit.normal faces the ray: entering from air (front face) or leaving the medium
        const vec3 d = glm::normalize(r.direction);
        const real eta = hit.front_face ? real(1) : m.ior;
        const real eta_t = hit.front_face ? m.ior : real(1);
        const color reflected = trace(reflect(d, hit.normal));
        vec3 t;
        if (refract(d, hit.normal, eta, eta_t, t)) {
            const real R = schlick_reflectance(-glm::dot(d, hit.normal), eta, eta_t);
            L += float(R) * reflected + float(1 - R) * trace(t);
        } else {
            L += reflected; // total internal reflection
        }
    }
    if (!hit.front_face) // the ray travelled t |d| inside the medium
        L *= beer_attenuation(m.attenuation, hit.t * glm::length(r.direction));
    return L;
    // RT_EXERCISE_END
}

/// True when some material of s is a dielectric: the scene needs ray_color_glass.
inline bool has_dielectric(const scene& s)
{
    for (const material& m : s.materials)
        if (is_dielectric(m))
            return true;
    return is_dielectric(s.default_material);
}

} // namespace rt
