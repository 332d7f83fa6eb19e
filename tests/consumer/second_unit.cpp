#include <rt/rt.hpp>

int count_rays(const rt::scene& s)
{
    const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
    int rays = 0;
    for (int j = 0; j < s.height; ++j)
        for (int i = 0; i < s.width; ++i)
            rays += glm::length(rt::pixel_ray(gen, i, j).direction) > 0 ? 1 : 0;
    return rays;
}
