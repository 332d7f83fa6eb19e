// support_frame.hpp - stage 08's whole frame, compiled once: the threaded
// renderer over the library's BVH and the stage-07 color (or a debug image)
// and the traced story of one pixel (support_frame.cpp), and the image stored
// through the color pipeline (support_output.cpp). Only the last includes the
// stage-08 exercises (encoding.hpp), so an edit to a tone map rebuilds it and
// stage 08's own files, never the renderer or the BVH.
//
//     const rt::render_result out = stage::render_scene(scene, rt::aov_kind::shaded, options, bar.callback());
//     stage::save_encoded("out.png", out.pixels, rt::aov_kind::shaded, rt::encoding{});
#pragma once

#include <functional>
#include <string>

#include <rt/output/aov.hpp>
#include <rt/core/image.hpp>
#include <rt/core/ray.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/scene/scene.hpp>
#include <rt/core/vec.hpp>

#include "pixel_story.hpp"

namespace rt {
struct encoding;
}

namespace stage {

/// rt::render of the color `radiance` gives each ray of `rays` (film position in pixels -> ray).
rt::render_result render_image(const rt::render_options& options,
                               const std::function<rt::ray(rt::real, rt::real)>& rays,
                               const std::function<rt::color(const rt::ray&, rt::sample_context&)>& radiance,
                               const rt::progress_callback& progress);

/// rt::render of scene `s` through its camera: the shaded color of stages
/// 05-07 (rt::make_radiance, the library's BVH) or the debug image `aov`.
rt::render_result render_scene(const rt::scene& s, rt::aov_kind aov, const rt::render_options& options,
                               const rt::progress_callback& progress);

/// The story of pixel (column, row) of an nx x ny image of scene `s`
/// (pixel_story.hpp): its centre's ray traced by the stage-07 color
/// (rt::ray_color over the library's BVH; stage 09's rt::ray_color_glass
/// where the scene has glass or a glossy mirror, as rt::make_radiance) with
/// the random numbers of the render's first sample (seed 0) for stage 10's
/// lens, area lights and gloss, every query recorded and named, the light
/// terms worked out; stage 08 adds what its pipeline makes of it.
story shaded_story(const rt::scene& s, const std::string& program, int column, int row, int nx, int ny);

/// rt::save_image_encoded through the color pipeline: `enc` for the shaded image,
/// rt::output_encoding's data encoding for a debug image of kind `aov`.
void save_encoded(const std::string& path, const rt::image& img, rt::aov_kind aov, const rt::encoding& enc);

/// The pixel story's last lines: what exposure, the tone map and the transfer
/// curve make of the traced color `st.linear`, down to the stored bytes.
void add_encoding_story(story& st, const rt::encoding& enc, int samples_per_pixel);

} // namespace stage
