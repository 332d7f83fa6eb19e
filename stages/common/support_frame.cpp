// Stage 08's renderer and its pixel story, compiled once (support_frame.hpp).
#include "support_frame.hpp"

#include <rt/dielectric.hpp>
#include <rt/radiance.hpp>
#include <rt/raytracer.hpp>
#include <rt/shading.hpp>

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
    return rt::render(options, rt::camera_rays(s.cam, options.width, options.height), rt::make_radiance(s, aov),
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
    // as rt::make_radiance does: stage 09's colour where the scene has glass
    const recording<world> traced(w, st.queries);
    st.linear = rt::has_dielectric(s) ? rt::ray_color_glass(s, traced, st.camera) : rt::ray_color(s, traced, st.camera);
    name_queries(st);
    explain_lights(st, s, true, false,
                   [](const rt::material& m, const rt::vec3& n, const rt::vec3& v, const rt::vec3& l,
                      const rt::color& I) { return rt::blinn_phong(m, n, v, l, I); });
    return st;
}

} // namespace stage
