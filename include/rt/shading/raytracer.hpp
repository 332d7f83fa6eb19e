// raytracer.hpp - the color seen along one ray: shading, shadows, mirrors (stage 07).
//
// Fundamentals of Computer Graphics, 4th ed., sec. 4.8 (ideal specular
// reflection): a mirror adds the color seen in the reflected direction,
//     L += km raycolor(p, r),   r = d - 2 (d.n) n,
// recursively, up to a maximum depth; rays that hit nothing see the background.
// The course's "Ray tracer: single ray" class.
#pragma once

#include <limits>

#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../scene/scene.hpp"
#include "shading.hpp"
#include "shadows.hpp"
#include "../intersection/spawn.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The mirror direction of d about the unit normal n: r = d - 2 (d.n) n.
inline vec3 reflect(const vec3& d, const vec3& n)
{
    // RT_EXERCISE_BEGIN(stage07: reflection direction)
    return d - real(2) * glm::dot(d, n) * n;
    // RT_EXERCISE_END
}

/// The color seen along ray r in scene s: background on a miss; otherwise the
/// direct light with shadows, plus km times the color seen in the mirror
/// direction while depth < s.max_depth. `accel` is built from s (rt::accelerator).
template <class Accelerator>
color ray_color(const scene& s, const Accelerator& accel, const ray& r, int depth = 0,
                const shading_options& options = {})
{
    // RT_EXERCISE_BEGIN(stage07: ray color with mirrors)
    hit_record hit;
    if (!accel.closest_hit(r, real(0), std::numeric_limits<real>::infinity(), hit))
        return s.background;
    color L = direct_lighting(
        s, hit, r.direction, [&](const light_sample& sample) { return light_visible(accel, hit, sample); }, options);
    const material& m = s.material_of(hit.material);
    const bool mirror = m.km.r > 0 || m.km.g > 0 || m.km.b > 0;
    if (mirror && depth < s.max_depth) {
        const ray reflected = spawn_ray(hit, reflect(r.direction, hit.normal));
        L += m.km * ray_color(s, accel, reflected, depth + 1, options);
    }
    return L;
    // RT_EXERCISE_END
}

} // namespace rt
