// Scene files and bare OBJ models for the stage programs, compiled once (support.hpp).
#include "support.hpp"

#include <rt/render_setup.hpp>

namespace stage {

rt::scene load_input(const std::string& path, std::optional<int> width, std::optional<int> height)
{
    return rt::load_input(path, width, height);
}

} // namespace stage
