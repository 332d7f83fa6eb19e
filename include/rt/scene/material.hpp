// material.hpp - how a surface reflects light (used from stage 05 on).
//
// Blinn-Phong with an ideal mirror term, Fundamentals of Computer Graphics,
// 4th ed., sec. 4.5-4.8: ambient ka, diffuse kd, specular ks with Phong
// exponent p, and mirror reflectance km. A dielectric (glass, water; stage 09,
// FCG sec. 13.1) has an index of refraction ior and an attenuation constant a
// per unit length inside it (Beer's law). A glossy mirror (stage 10, FCG sec.
// 13.4.4) reflects around the mirror direction, blurred by the side a of a
// square of perturbations (glossy.hpp). A surface that glows (stage 11's area
// lights, an MTL file's Ke) emits the radiance Le from its front side.
// Defaults are those of docs/scene-format.md: a matte light grey that emits
// nothing.
#pragma once

#include <string>

#include "../core/config.hpp"
#include "../core/vec.hpp"

namespace rt {

struct material {
    std::string name = "default";
    color ka{0.8f};  ///< ambient reflectance (the scene file defaults it to kd)
    color kd{0.8f};  ///< diffuse reflectance
    color ks{0.0f};  ///< specular reflectance
    real p = 32;     ///< Phong exponent of the specular highlight
    color km{0.0f};  ///< mirror reflectance
    real ior = 0;    ///< index of refraction of a dielectric (glass 1.5, water 1.33); 0: opaque
    color attenuation{0.0f};  ///< a dielectric's Beer attenuation a per unit length: exp(-a s) is left after s
    real glossy = 0;  ///< a mirror's blur: the side a of the square of perturbations; 0: a perfect mirror
    color emission{0.0f};  ///< Le, the radiance the surface emits (stage 11); 0: none
};

/// True for a material that emits light (stage 11): a path that meets it gains Le.
inline bool is_emissive(const material& m)
{
    return m.emission.r > 0 || m.emission.g > 0 || m.emission.b > 0;
}

/// True for a dielectric (stage 09): light enters it, refracted.
inline bool is_dielectric(const material& m)
{
    return m.ior > 0;
}

} // namespace rt
