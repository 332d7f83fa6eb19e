// The scene reader for the stage programs, compiled once (support.hpp).
#include "support.hpp"

#include <rt/input/scene_loader.hpp>

#include "command_line.hpp" // file_argument

namespace stage {

rt::scene load_scene(const std::string& path, bool strict)
{
    rt::load_options options;
    options.obj.strict = strict;
    return rt::load_scene(file_argument(path), options);
}

} // namespace stage
