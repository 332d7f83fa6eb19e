// ray_image.hpp - look at the rays before anything is intersected (stage 02).
//
// The course: "Generate rays; print x, y, z as image". Each pixel shows its
// ray's unit direction d^ mapped from [-1, 1] to [0, 1] per channel:
//     (r, g, b) = (d^ + 1) / 2
// so a ray pointing right is reddish, up greenish, towards the viewer bluish;
// straight ahead (-z) is (0.5, 0.5, 0).
#pragma once

#include "camera.hpp"
#include "../core/image.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The color that shows a direction: (d/|d| + 1) / 2 per channel.
inline color direction_to_color(const vec3& d)
{
    // RT_EXERCISE_BEGIN(stage02: direction as color)
    const vec3 unit = glm::normalize(d);
    return color((unit + vec3(1)) * real(0.5));
    // RT_EXERCISE_END
}

/// An image whose pixel (i, j) shows the direction of the ray through its centre.
inline image render_ray_directions(const ray_generator& gen)
{
    image img(gen.nx, gen.ny);
    for (int j = 0; j < gen.ny; ++j)
        for (int i = 0; i < gen.nx; ++i)
            img.at(i, gen.ny - 1 - j) = direction_to_color(pixel_ray(gen, i, j).direction);
    return img;
}

} // namespace rt
