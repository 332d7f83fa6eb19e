// The scene reader for the stage programs, compiled once (support.hpp).
#include "support.hpp"

#include <rt/scene_loader.hpp>

namespace stage {

rt::scene load_scene(const std::string& path) { return rt::load_scene(path); }

} // namespace stage
