// Stage 08's renderer and its pixel story, compiled once (support_frame.hpp).
#include "support_frame.hpp"

#include <cstdint>
#include <memory>

#include <rt/shading/dielectric.hpp>
#include <rt/shading/glossy.hpp>
#include <rt/core/random.hpp>
#include <rt/rendering/radiance.hpp>
#include <rt/shading/raytracer.hpp>
#include <rt/shading/shading.hpp>

#include "light_terms.hpp"
#include "support.hpp"

namespace stage {

rt::render_result render_image(const rt::render_options& options,
                               const std::function<rt::ray(rt::real, rt::real)>& rays,
                               const std::function<rt::color(const rt::ray&, rt::sample_context&)>& radiance,
                               const rt::progress_callback& progress)
{
    return rt::render(options, rays, radiance, progress);
}

rt::render_result render_scene(const rt::scene& s, rt::aov_kind aov, const rt::render_options& options,
                               const rt::progress_callback& progress)
{
    // the accelerator built by support_world.cpp: this file compiles only its queries
    // (an edit to a stage-10 header rebuilds it in half the time)
    std::shared_ptr<const rt::accelerator> accel;
    if (aov != rt::aov_kind::rays)
        accel = world(s).shared();
    return rt::render(options, rt::camera_rays(s.cam, options.width, options.height), rt::make_radiance(s, accel, aov),
                      progress);
}

story shaded_story(const rt::scene& s, const std::string& program, int column, int row, int nx, int ny)
{
    const world w(s);
    const rt::ray_generator gen = rt::make_ray_generator(s.cam, nx, ny);
    story st;
    st.program = program;
    place_pixel(st, column, row, gen.nx, gen.ny);
    st.camera = rt::pixel_ray(gen, st.i, st.j);
    // as rt::make_radiance does for the render's first sample of this pixel, at
    // the pixel's centre: stage 09's color where the scene has glass or a glossy
    // mirror, and stage 10's random numbers for the lens, area lights and gloss
    rt::pcg32 random = rt::seeded_generator(0, std::uint64_t(row) * std::uint64_t(nx) + std::uint64_t(column), 1,
                                            rt::integrator_stream);
    rt::shading_options options;
    options.random = &random;
    st.camera = rt::lens_ray(s, st.camera, random);
    const recording<world> traced(w, st.queries);
    st.linear = rt::has_dielectric(s) || rt::has_glossy(s) ? rt::ray_color_glass(s, traced, st.camera, 0, options)
                                                           : rt::ray_color(s, traced, st.camera, 0, options);
    name_queries(st);
    explain_lights(
        st, s, true, false,
        [](const rt::material& m, const rt::vec3& n, const rt::vec3& v, const rt::vec3& l, const rt::color& I) {
            return rt::blinn_phong(m, n, v, l, I);
        },
        true);
    return st;
}

} // namespace stage
