// thin_lens.hpp - depth of field with a thin lens (stage 10).
//
// A pinhole camera (stage 02) sends every ray of a pixel from the eye e, so
// everything is sharp. A real lens has an opening: light from one point of the
// scene reaches the film through every point of the lens, and only points on
// the plane in focus meet again in one point of the film. Distribution ray
// tracing (Cook, Porter, Carpenter 1984; Fundamentals of Computer Graphics,
// 4th ed., sec. 13.4.3; Physically Based Rendering, 3rd ed., sec. 6.2.3)
// gives each sample a random point of the lens and aims it at the point where
// the pinhole ray meets the plane in focus: points on that plane stay sharp,
// and a point at distance z along the view blurs into a disk of radius
// aperture |1 - z / focus| around where the pinhole sees it (similar triangles).
//
//     const rt::vec2 lens = rt::concentric_disk(xi1, xi2);    // a point of the unit disk
//     const rt::ray r = rt::thin_lens_ray(pinhole, gen.basis, aperture, focus, lens);
#pragma once

#include <cmath>

#include <glm/geometric.hpp>

#include "camera.hpp"
#include "../core/config.hpp"
#include "../core/ray.hpp"
#include "../core/vec.hpp"

namespace rt {

/// A point of the unit disk from (xi1, xi2) in [0, 1)^2, equal areas to equal
/// areas (so uniform stays uniform), squares to rings with little distortion:
/// P. Shirley, K. Chiu, "A Low Distortion Map Between Disk and Square",
/// Journal of Graphics Tools 2(3), 1997. The square [-1, 1]^2 is cut into four
/// triangles by its diagonals; in each, the larger coordinate is the radius
/// and the other the angle within that quarter.
inline vec2 concentric_disk(real xi1, real xi2)
{
    const real a = 2 * xi1 - 1, b = 2 * xi2 - 1;
    if (a == 0 && b == 0)
        return vec2(0);
    const real quarter = real(0.78539816339744830962); // pi / 4
    real radius, phi;
    if (std::fabs(a) > std::fabs(b)) {
        radius = a;
        phi = quarter * (b / a);
    } else {
        radius = b;
        phi = 2 * quarter - quarter * (a / b);
    }
    return radius * vec2(std::cos(phi), std::sin(phi));
}

/// The thin-lens ray for the pinhole ray `pinhole` (from e, stage 02) and the
/// point `lens` of the unit disk: it starts at e + aperture (lens.x u + lens.y v)
/// and passes through the point where the pinhole ray meets the plane in focus,
/// the plane at distance `focus` from e along -w (the view direction).
inline ray thin_lens_ray(const ray& pinhole, const frame& basis, real aperture, real focus, const vec2& lens)
{
    // RT_EXERCISE_BEGIN(stage10: the thin-lens ray)
    // the pinhole ray reaches the plane in focus where its progress along -w is `focus`
    const real along = -glm::dot(pinhole.direction, basis.w);
    const vec3 in_focus = pinhole.origin + (focus / along) * pinhole.direction;
    const vec3 origin = pinhole.origin + aperture * (lens.x * basis.u + lens.y * basis.v);
    return ray{origin, in_focus - origin};
    // RT_EXERCISE_END
}

} // namespace rt
