// next_event.hpp - next-event estimation: aiming at the lights on purpose (stage 11).
//
// A path that only follows BSDF directions finds a small light by chance, so
// most of its samples see none and the image is noisy. Next-event estimation
// (PBR 4th ed., sec. 13.4; "direct lighting by light sampling") takes at each
// point x a random point y of the emitters (emitters.hpp), drawn with the
// density pdf_A per unit area, and traces a shadow ray to it. The rendering
// equation integrates over directions; a density over area becomes one over
// solid angle with the change of variables dw = |cos(theta_y)| dA / d^2
// (PBR 4th ed., sec. 4.2.3), d = |y - x|:
//     pdf_w = pdf_A d^2 / |cos(theta_y)|,
// theta_y the angle at y between its normal and the direction back to x. For a
// Lambertian x of albedo rho with normal n, w = (y - x) / d, the estimate is
//     f Le cos(theta_x) / pdf_w,   f = rho / pi,  cos(theta_x) = n . w,
// and 0 when y is behind x (cos(theta_x) <= 0), or x behind y (the light
// glows from its front only: y.normal . w >= 0), or y seen edge-on. The
// caller traces the shadow ray and weighs the estimate (mis.hpp).
//
//     const rt::emitter_sample y = rt::sample_emitters(lights, xi0, xi1, xi2);
//     const rt::color direct = rt::next_event_estimate(m.kd, hit.point, hit.normal, y);
#pragma once

#include <cmath>

#include <glm/geometric.hpp>

#include "../core/config.hpp"
#include "emitters.hpp"
#include "lambertian.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The density per unit solid angle, seen from a point at `distance`, of a
/// point drawn with `pdf_area` per unit area on a surface whose normal makes
/// the angle theta_y (cos_y = its cosine) with the direction back: pdf_A d^2 /
/// |cos_y| (PBR 4th ed., sec. 4.2.3); 0 when cos_y is 0 (seen edge-on).
inline real solid_angle_pdf(real pdf_area, real distance, real cos_y)
{
    // RT_EXERCISE_BEGIN(stage11: area density to solid-angle density)
    const real c = std::fabs(cos_y);
    if (!(c > 0))
        return 0;
    return pdf_area * distance * distance / c;
    // RT_EXERCISE_END
}

/// The next-event estimate f Le cos(theta_x) / pdf_w at the point x (unit
/// normal n, on the side of the light that counts) of a Lambertian surface of
/// albedo `albedo`, for the emitter point y, before the shadow ray and the MIS
/// weight: 0 when y is below x's surface, when x is behind the light (y.normal
/// is its front) or when y is seen edge-on.
inline color next_event_estimate(const color& albedo, const vec3& x, const vec3& n, const emitter_sample& y)
{
    // RT_EXERCISE_BEGIN(stage11: next-event estimation)
    // hint: w = (y.point - x) / d; cos_x = n . w; the light faces x when y.normal . w < 0
    const vec3 to_light = y.point - x;
    const real d = glm::length(to_light);
    if (!(d > 0) || !(y.pdf_area > 0))
        return color(0.0f);
    const vec3 w = to_light / d;
    const real cos_x = glm::dot(n, w);
    const real cos_y = glm::dot(y.normal, w);
    if (!(cos_x > 0) || !(cos_y < 0))
        return color(0.0f);
    const real pdf_w = solid_angle_pdf(y.pdf_area, d, cos_y);
    return lambertian_brdf(albedo) * y.emission * float(cos_x / pdf_w);
    // RT_EXERCISE_END
}

} // namespace rt
