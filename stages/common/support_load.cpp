// The scene reader for the stage programs, compiled once (support.hpp).
#include "support.hpp"

#include <rt/scene_loader.hpp>

namespace stage {

rt::scene load_scene(const std::string& path, bool strict)
{
    rt::load_options options;
    options.obj.strict = strict;
    return rt::load_scene(path, options);
}

} // namespace stage
