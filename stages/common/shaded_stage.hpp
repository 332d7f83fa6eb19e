// shaded_stage.hpp - what the stage 05, 06 and 07 programs share: read
// "SCENE [-o OUTPUT] [stage options]", build the scene's accelerator, render
// one centred sample per pixel with the stage's colour function, and store it.
#pragma once

#include <cstdint>
#include <functional>
#include <iostream>
#include <string>

#include <rt/atomic_file.hpp>
#include <rt/camera.hpp>
#include <rt/image_io.hpp>
#include <rt/intersect.hpp>
#include <rt/renderer.hpp>
#include <rt/scene.hpp>
#include <rt/scene_loader.hpp>

#include "stage_main.hpp"

namespace stage {

/// The colour of one camera ray, given the scene and its accelerator.
using color_function = std::function<rt::color(const rt::scene&, const rt::accelerator&, const rt::ray&)>;

/// Renders `scene_path` with `shade` to `output` (format from the extension);
/// `adjust` may change the loaded scene first (a command-line override).
inline void render_shaded(const std::string& program, const std::string& scene_path, const std::string& output,
                          const color_function& shade, const std::function<void(rt::scene&)>& adjust = {})
{
    rt::check_image_output(output); // every option, the output format included, before any work
    check_input_and_outputs(scene_path, "a scene file", {output});
    rt::scene s = rt::load_scene(scene_path);
    rt::check_not_input(output, rt::files_read(scene_path, s)); // its OBJ and MTL files too
    if (adjust)
        adjust(s);
    // the image (three floats a pixel) and its bytes
    rt::check_memory_for(std::uint64_t(s.width) * std::uint64_t(s.height) * (12 + 3),
                         "a " + std::to_string(s.width) + "x" + std::to_string(s.height) + " image");
    const rt::accelerator accel(s);
    rt::render_options options;
    options.width = s.width;
    options.height = s.height;
    options.samples_per_pixel = 1;
    options.sampler = rt::sampler_kind::center; // one ray through each pixel centre, as in the book
    const rt::ray_generator gen = rt::make_ray_generator(s.cam, s.width, s.height);
    const rt::render_result result = rt::render(
        options, [&gen](rt::real x, rt::real y) { return rt::generate_ray(gen, x, y); },
        [&](const rt::ray& r, rt::sample_context&) { return shade(s, accel, r); });
    rt::save_image(output, result.pixels, 2.2f);
    std::cerr << program << ": wrote " << output << " (" << s.width << "x" << s.height << ")\n";
}

} // namespace stage
