// refraction.hpp - light through a dielectric (glass, water): the refracted
// direction, how much is reflected instead, and how much the medium absorbs.
// Stage 09: refract and schlick_reflectance are exercises (tests/stage09_refraction.cpp);
// the exact Fresnel equations and Beer's law are given (tests/library_refraction.cpp).
//
//     rt::vec3 t;
//     if (rt::refract(d, n, 1.0f, 1.5f, t)) ...          // air into glass; false: total internal reflection
//     const rt::real R = rt::schlick_reflectance(cos_theta, 1.0f, 1.5f);   // the part reflected
//     const rt::color k = rt::beer_attenuation(a, distance);               // what is left after `distance`
//
// Fundamentals of Computer Graphics (Shirley, Marschner), 4th ed., sec. 13.1
// ("Transparency and Refraction"), with the book's symbols: d the unit
// incoming direction, n the unit normal on the side d comes from (d.n < 0),
// eta and eta_t the refractive indices of the medium d travels in and of the
// one it enters (the book writes n and n_t), t the transmitted direction.
// Snell's law, eta sin(theta) = eta_t sin(phi), gives
//     t = eta (d - n (d.n)) / eta_t - n sqrt(1 - eta^2 (1 - (d.n)^2) / eta_t^2)
// and no t when the root's argument is negative (total internal reflection).
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "../core/config.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The cosine of the refracted angle phi for incidence cosine `cos_theta`
/// (Snell's law), or -1 on total internal reflection.
inline real refracted_cosine(real cos_theta, real eta, real eta_t)
{
    const real ratio = eta / eta_t;
    const real sin2_phi = ratio * ratio * std::max(real(0), real(1) - cos_theta * cos_theta);
    return sin2_phi > real(1) ? real(-1) : std::sqrt(real(1) - sin2_phi);
}

/// The refracted direction of unit `d` at a surface of unit normal `n` facing
/// it (d.n <= 0), from index `eta` into index `eta_t` (FCG 4th ed., sec. 13.1):
/// true and the unit direction in `t`, or false on total internal reflection
/// (t untouched). Both indices must be positive.
inline bool refract(const vec3& d, const vec3& n, real eta, real eta_t, vec3& t)
{
    // RT_EXERCISE_BEGIN(stage09: refracted direction)
    // Hint: refracted_cosine (above) is Snell's law for the cosines.
    const real cos_theta = -glm::dot(d, n); // cos of the angle of incidence, >= 0
    const real cos_phi = refracted_cosine(cos_theta, eta, eta_t);
    if (cos_phi < 0)
        return false;                        // beyond the critical angle
    t = (eta / eta_t) * (d + n * cos_theta) - n * cos_phi; // d - n (d.n) = d + n cos(theta)
    return true;
    // RT_EXERCISE_END
}

/// The reflectance of a smooth dielectric boundary for unpolarised light, by
/// the Fresnel equations (Pharr, Jakob, Humphreys, Physically Based Rendering,
/// 3rd ed., sec. 8.2.1, eq. 8.2-8.3):
///     r_par  = (eta_t cos(theta) - eta cos(phi)) / (eta_t cos(theta) + eta cos(phi))
///     r_perp = (eta cos(theta) - eta_t cos(phi)) / (eta cos(theta) + eta_t cos(phi))
///     R = (r_par^2 + r_perp^2) / 2,
/// 1 on total internal reflection. `cos_theta` is the incidence cosine (>= 0).
inline real fresnel_reflectance(real cos_theta, real eta, real eta_t)
{
    const real cos_phi = refracted_cosine(cos_theta, eta, eta_t);
    if (cos_phi < 0)
        return real(1);
    const real r_par = (eta_t * cos_theta - eta * cos_phi) / (eta_t * cos_theta + eta * cos_phi);
    const real r_perp = (eta * cos_theta - eta_t * cos_phi) / (eta * cos_theta + eta_t * cos_phi);
    return (r_par * r_par + r_perp * r_perp) / real(2);
}

/// Schlick's approximation of fresnel_reflectance (C. Schlick, "An
/// Inexpensive BRDF Model for Physically-based Rendering", Computer Graphics
/// Forum 13(3), 1994; FCG 4th ed., sec. 13.1):
///     R = R0 + (1 - R0) (1 - cos)^5,   R0 = ((eta_t - eta) / (eta_t + eta))^2,
/// with cos the cosine of the larger of the two angles, the one on the side of
/// the lower index (the incidence angle from air into glass, the refracted
/// angle from glass into air), and 1 on total internal reflection.
inline real schlick_reflectance(real cos_theta, real eta, real eta_t)
{
    // RT_EXERCISE_BEGIN(stage09: Schlick's reflectance)
    real cosine = cos_theta;
    if (eta > eta_t) {
        cosine = refracted_cosine(cos_theta, eta, eta_t);
        if (cosine < 0)
            return real(1);
    }
    const real r0 = ((eta_t - eta) / (eta_t + eta)) * ((eta_t - eta) / (eta_t + eta));
    const real m = real(1) - cosine;
    return r0 + (real(1) - r0) * m * m * m * m * m;
    // RT_EXERCISE_END
}

/// What is left of light after `distance` inside a medium of attenuation
/// constant `a` per unit length (Beer's law, FCG 4th ed., sec. 13.1):
/// exp(-a distance) in each channel.
inline color beer_attenuation(const color& a, real distance)
{
    const float s = float(distance);
    return color(std::exp(-a.r * s), std::exp(-a.g * s), std::exp(-a.b * s));
}

} // namespace rt
