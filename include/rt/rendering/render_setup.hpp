// render_setup.hpp - everything the render commands share between the command
// line and rt::render, in one include: scene_input.hpp (a scene file or a bare
// OBJ), aov.hpp (what each sample computes and how it is stored), radiance.hpp
// (the camera's rays and their color), camera_text.hpp and
// camera_statement.hpp (the camera as text, both ways), encoded_output.hpp
// (images through the color pipeline). Include the one you
// use: this umbrella pulls in both loaders and the renderer.
//
// stage08_output and the interactive viewer (stages/viewer) both build their
// renders from these pieces, so the viewer shows, pixel for pixel, what
// stage08_output writes for the same camera and settings:
//
//     rt::scene s = rt::load_input("scenes/showcase.scene");
//     const rt::radiance_function radiance = rt::make_radiance(s, rt::aov_kind::shaded); // shaded
//     const rt::ray_source rays = rt::camera_rays(s.cam, s.width, s.height);
//     rt::render_result out = rt::render(options, rays, radiance);
//     rt::save_image_encoded("out.png", out.pixels, rt::output_encoding(rt::aov_kind::shaded, rt::encoding{}, out.pixels));
#pragma once

#include "../output/aov.hpp"
#include "../input/camera_statement.hpp"
#include "../camera/camera_text.hpp"
#include "../output/encoded_output.hpp"
#include "radiance.hpp"
#include "scene_input.hpp"
