// hemisphere.hpp - random directions above a surface, and their densities (stage 11).
//
// The rendering equation integrates over the hemisphere of directions above a
// point (J. T. Kajiya, "The Rendering Equation", SIGGRAPH 1986). A Monte Carlo
// estimate draws directions w with a density p(w) per unit solid angle and
// averages f(w) / p(w) (Physically Based Rendering, 4th ed., sec. 2.1.3). Two
// densities over the hemisphere about the z axis, from two uniform numbers in
// [0, 1):
//
// uniform (given; PBR 4th ed., sec. A.5; 3rd ed., sec. 13.6.1): z = xi1, phi = 2 pi xi2, p = 1 / (2 pi);
// cosine-weighted (the exercise; Malley's method, PBR 4th ed., sec. A.5; 3rd ed., sec. 13.6.3):
// a point (x, y) spread evenly over the unit disk (concentric_disk), lifted
// onto the hemisphere, z = sqrt(1 - x^2 - y^2). The density is
//     p(w) = cos(theta) / pi,   cos(theta) = w.z,
// so more directions go where the cosine of the rendering equation is large.
//
// A direction about the z axis turns into one about a surface normal n with
// to_world (T. Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
//
//     const rt::vec3 local = rt::cosine_hemisphere(xi1, xi2);  // local.z = cos(theta) >= 0
//     const rt::real pdf = rt::cosine_hemisphere_pdf(local.z);
//     const rt::vec3 w = rt::to_world(local, n);
#pragma once

#include <algorithm>
#include <cmath>

#include "../core/config.hpp"
#include "../camera/thin_lens.hpp" // concentric_disk
#include "../core/vec.hpp"

namespace rt {

/// pi, in rt::real.
constexpr real pi_real = real(3.14159265358979323846);

/// A unit direction with z >= 0, uniform over the hemisphere (PBR 4th ed., sec. A.5).
inline vec3 uniform_hemisphere(real xi1, real xi2)
{
    const real z = xi1;
    const real r = std::sqrt(std::max(real(0), 1 - z * z));
    const real phi = 2 * pi_real * xi2;
    return vec3(r * std::cos(phi), r * std::sin(phi), z);
}

/// The density of uniform_hemisphere per unit solid angle: 1 / (2 pi).
inline real uniform_hemisphere_pdf()
{
    return 1 / (2 * pi_real);
}

/// A unit direction with z >= 0 whose density is cos(theta) / pi: a point of
/// the unit disk from (xi1, xi2), even over its area, lifted onto the
/// hemisphere (Malley's method, PBR 4th ed., sec. A.5).
inline vec3 cosine_hemisphere(real xi1, real xi2)
{
    // RT_EXERCISE_BEGIN(stage11: cosine-weighted hemisphere sampling)
    // hint: concentric_disk(xi1, xi2) (thin_lens.hpp) gives the point of the disk
    const vec2 d = concentric_disk(xi1, xi2);
    const real z = std::sqrt(std::max(real(0), 1 - d.x * d.x - d.y * d.y));
    return vec3(d.x, d.y, z);
    // RT_EXERCISE_END
}

/// The density of cosine_hemisphere per unit solid angle at a direction whose
/// z is cos_theta: cos(theta) / pi (0 below the surface).
inline real cosine_hemisphere_pdf(real cos_theta)
{
    // RT_EXERCISE_BEGIN(stage11: the cosine density)
    return std::max(real(0), cos_theta) / pi_real;
    // RT_EXERCISE_END
}

/// The direction `local`, given about the z axis, turned about the unit
/// normal n: local.x t + local.y b + local.z n, with (t, b, n) orthonormal
/// (Duff et al. 2017, without a branch on a near-zero component).
inline vec3 to_world(const vec3& local, const vec3& n)
{
    const real sign = std::copysign(real(1), n.z);
    const real a = -1 / (sign + n.z);
    const real b = n.x * n.y * a;
    const vec3 t(1 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    const vec3 bt(b, sign + n.y * n.y * a, -n.y);
    return local.x * t + local.y * bt + local.z * n;
}

} // namespace rt
