// support.hpp - the heavy parts of the stage programs that a student's edit
// rarely touches (reading a scene file, writing an image), compiled once into
// the library rt_stage_support (stages/CMakeLists.txt) rather than in every
// program. An edit to an exercise header then rebuilds only the stage's own
// main.cpp and test suite: a few seconds instead of a minute.
//
//     const rt::scene s = stage::load_scene("scenes/showcase.scene");
//     stage::save_image("out.png", pixels, 2.2f);
//
// Each function is the library's own (rt::load_scene, rt::save_image); only
// where it is compiled differs.
#pragma once

#include <string>

#include <rt/image.hpp>
#include <rt/scene.hpp>

namespace stage {

/// rt::load_scene: the scene file at `path`, or an rt::error naming file:line:col.
rt::scene load_scene(const std::string& path);

/// rt::save_image: `img` to `path` (.png, .ppm or .pfm), written atomically;
/// 8-bit formats clamp and apply 1/gamma (1: bytes proportional to the values).
void save_image(const std::string& path, const rt::image& img, float gamma = 2.2f);

} // namespace stage
