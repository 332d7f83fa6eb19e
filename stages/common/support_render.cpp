// The threaded renderer for the stage programs, compiled once (support.hpp).
#include "support.hpp"

#include <rt/rendering/renderer.hpp>

namespace stage {

rt::image render_centres(int nx, int ny, const ray_source& rays, const color_function& color)
{
    rt::render_options options;
    options.width = nx;
    options.height = ny;
    options.samples_per_pixel = 1;
    options.sampler = rt::sampler_kind::center; // one ray through each pixel centre, as in the book
    return rt::render(options, rays, [&color](const rt::ray& r, rt::sample_context&) { return color(r); }).pixels;
}

} // namespace stage
