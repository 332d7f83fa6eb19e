// Scene files and bare OBJ models for the stage programs, compiled once (support.hpp).
#include "support.hpp"

#include <rt/rendering/scene_input.hpp>

#include "command_line.hpp" // file_argument

namespace stage {

rt::scene load_input(const std::string& path, std::optional<int> width, std::optional<int> height, bool strict)
{
    rt::load_options options;
    options.obj.strict = strict;
    return rt::load_input(file_argument(path), width, height, options);
}

} // namespace stage
