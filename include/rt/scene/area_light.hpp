// area_light.hpp - a random point on an area light (stage 10).
//
// Distribution ray tracing (R. L. Cook, T. Porter, L. Carpenter, "Distributed
// Ray Tracing", SIGGRAPH 1984; Fundamentals of Computer Graphics, 4th ed.,
// sec. 13.4.2) makes a soft shadow by aiming each sample's shadow ray at a
// different random point of the light: an area light of intensity I acts, for
// one sample, as a point light of intensity I at that point, and averaging the
// samples of a pixel averages over the light. Where part of the light is
// hidden, part of the samples are in shadow: the penumbra.
//
// Each function turns two uniform random numbers xi1, xi2 in [0, 1) into a
// point of the light, spread so that equal areas of [0, 1)^2 go to equal
// parts of the light:
//
//     rt::vec3 y = rt::sample_rect_light(corner, edge1, edge2, xi1, xi2);
//     rt::vec3 y = rt::sample_sphere_light(center, radius, x, xi1, xi2);
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "../core/config.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The point c + xi1 a + xi2 b of the parallelogram light with corner c and
/// edges a, b (FCG 4th ed., sec. 13.4.2): uniform over its area.
inline vec3 sample_rect_light(const vec3& c, const vec3& a, const vec3& b, real xi1, real xi2)
{
    // RT_EXERCISE_BEGIN(stage10: a point on a rectangle light)
    return c + xi1 * a + xi2 * b;
    // RT_EXERCISE_END
}

/// A point of the sphere light (center, radius) as seen from x outside it,
/// uniform in the solid angle the sphere covers seen from x (Physically Based
/// Rendering, 3rd ed., sec. 14.2.3): the directions from x that meet the
/// sphere form a cone about w = (center - x)/|center - x| with
/// cos(theta_max) = sqrt(1 - R^2 / D^2), D = |center - x|; take
///     cos(theta) = (1 - xi1) + xi1 cos(theta_max),   phi = 2 pi xi2,
/// the direction sin(theta) cos(phi) u + sin(theta) sin(phi) v + cos(theta) w
/// (u, v, w orthonormal), and return where it first meets the sphere:
/// x + s dir, s = D cos(theta) - sqrt(R^2 - D^2 sin^2(theta)).
inline vec3 sample_sphere_light(const vec3& center, real radius, const vec3& x, real xi1, real xi2)
{
    // RT_EXERCISE_BEGIN(stage10: a point on a sphere light)
    const vec3 to_center = center - x;
    const real D2 = glm::dot(to_center, to_center), D = std::sqrt(D2);
    const vec3 w = to_center / D;
    // any unit vector not parallel to w gives the rest of the frame
    const vec3 helper = std::fabs(w.x) > real(0.9) ? vec3(0, 1, 0) : vec3(1, 0, 0);
    const vec3 u = glm::normalize(glm::cross(helper, w));
    const vec3 v = glm::cross(w, u);
    const real cos_max = std::sqrt(std::max(real(0), 1 - radius * radius / D2));
    const real cos_theta = (1 - xi1) + xi1 * cos_max;
    const real sin_theta = std::sqrt(std::max(real(0), 1 - cos_theta * cos_theta));
    const real phi = real(6.28318530717958647692) * xi2;
    const vec3 dir = sin_theta * std::cos(phi) * u + sin_theta * std::sin(phi) * v + cos_theta * w;
    const real s = D * cos_theta - std::sqrt(std::max(real(0), radius * radius - D2 * sin_theta * sin_theta));
    return x + s * dir;
    // RT_EXERCISE_END
}

} // namespace rt
