// shading.hpp - Blinn-Phong shading (stage 05).
//
// Fundamentals of Computer Graphics (Shirley, Marschner), 4th ed., sec. 4.5.3
// and 4.5.4 (eq. 4.3 for several lights):
//     L = ka Ia + sum_i [ kd I_i max(0, n.l_i) + ks I_i max(0, n.h_i)^p ]
// with n the unit surface normal, v the unit direction to the viewer, l_i the
// unit direction to light i and h_i = (v + l_i)/|v + l_i| the half vector.
// Colors multiply channel by channel; everything stays linear until output.
#pragma once

#include <cmath>
#include <optional>

#include "../core/hit_record.hpp"
#include "../scene/light_sample.hpp"
#include "../scene/material.hpp"
#include "../core/random.hpp"
#include "../scene/scene.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The light one source reflects towards the viewer (the bracket of eq. 4.3):
/// kd I max(0, n.l) + ks I max(0, n.h)^p. n, v, l are unit vectors.
inline color blinn_phong(const material& m, const vec3& n, const vec3& v, const vec3& l, const color& I)
{
    // RT_EXERCISE_BEGIN(stage05: Blinn-Phong shading)
    const vec3 h = glm::normalize(v + l);
    const float diffuse = float(std::max(real(0), glm::dot(n, l)));
    const float specular = float(std::pow(std::max(real(0), glm::dot(n, h)), m.p));
    return m.kd * I * diffuse + m.ks * I * specular;
    // RT_EXERCISE_END
}

struct shading_options {
    bool light_falloff = false;  ///< point lights fall off as 1/r^2 (the book: off)
    /// Stage 10: the sample's random numbers. With them, each area light is seen
    /// from a new random point of it and a glossy mirror reflects in a random
    /// direction near the mirror direction; without (nullptr, stages 05-09), an
    /// area light shines from its centre and a glossy mirror is a perfect one.
    pcg32* random = nullptr;
};

/// The direct light at a hit seen along direction d: the ambient term plus
/// every light that `visible(sample)` says reaches the point (stage 06 passes a
/// shadow test; stage 05 passes "always"). A light behind the surface, as seen
/// from the viewer's side, contributes nothing. With options.random, each area
/// light is sampled at one random point (stage 10: one shadow ray per light).
template <class Visibility>
color direct_lighting(const scene& s, const hit_record& hit, const vec3& d, Visibility&& visible,
                      const shading_options& options = {})
{
    const material& m = s.material_of(hit.material);
    color L = m.ka * s.ambient;
    const vec3 v = -glm::normalize(d);
    for (const light& source : s.lights) {
        std::optional<vec2> xi;
        if (options.random && is_area_light(source)) {
            // two statements: the order of a call's arguments is unspecified, and
            // the image must not depend on the compiler
            const real xi1 = options.random->next_float();
            const real xi2 = options.random->next_float();
            xi = vec2(xi1, xi2);
        }
        const light_sample sample = sample_light(source, hit.point, options.light_falloff, xi);
        if (glm::dot(hit.geometric_normal, sample.l) <= 0)
            continue; // the light is behind the surface: it cannot light this side
        if (!visible(sample))
            continue;
        L += blinn_phong(m, hit.normal, v, sample.l, sample.intensity);
    }
    return L;
}

} // namespace rt
