// lambertian.hpp - a matte surface's BRDF, and the direction a path takes from it (stage 11).
//
// A Lambertian surface of albedo rho (the material's kd) scatters the light it
// receives equally into every direction above it: its BRDF is the constant
//     f = rho / pi
// (Physically Based Rendering, 4th ed., sec. 9.2; pi so that no more than
// rho of the light comes back out). The light it sends towards the eye is
// the integral over the hemisphere of f L(w) cos(theta) dw. With one
// direction w drawn with density p(w), the estimate is
//     f L(w) cos(theta) / p(w) = weight L(w),   weight = f cos(theta) / p(w),
// and a path tracer carries the weight along the path (its throughput).
// With the cosine density p = cos(theta) / pi the weight is rho itself: the
// cosine and the pi cancel (BSDF sampling, PBR 4th ed., sec. 13.3).
//
//     const rt::bsdf_sample next = rt::sample_lambertian(m.kd, hit.normal, xi1, xi2);
//     throughput *= next.weight; // then follow next.direction
#pragma once

#include "../core/config.hpp"
#include "hemisphere.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The BRDF of a Lambertian surface of albedo rho: rho / pi, for every pair of directions.
inline color lambertian_brdf(const color& albedo)
{
    return albedo / float(pi_real);
}

/// A direction drawn from a surface, with its density and the estimator's weight.
struct bsdf_sample {
    vec3 direction{0, 0, 1};  ///< unit, on the side of the normal
    real pdf = 0;             ///< p(w) per unit solid angle
    color weight{0.0f};       ///< f cos(theta) / p(w)
};

/// The next direction of a path from a Lambertian surface of albedo `albedo`
/// with the unit normal n (on the side the path arrives from): drawn from the
/// cosine density about n, with its pdf and the weight f cos(theta) / pdf.
inline bsdf_sample sample_lambertian(const color& albedo, const vec3& n, real xi1, real xi2)
{
    // RT_EXERCISE_BEGIN(stage11: the Lambertian BRDF estimator)
    // hint: cosine_hemisphere and cosine_hemisphere_pdf about z, then to_world(local, n)
    const vec3 local = cosine_hemisphere(xi1, xi2);
    bsdf_sample s;
    s.direction = to_world(local, n);
    s.pdf = cosine_hemisphere_pdf(local.z);
    if (s.pdf > 0)
        s.weight = lambertian_brdf(albedo) * float(local.z / s.pdf);
    return s;
    // RT_EXERCISE_END
}

} // namespace rt
