// The image writer for the stage programs, compiled once (support.hpp).
#include "support.hpp"

#include <rt/image_io.hpp>

namespace stage {

void save_image(const std::string& path, const rt::image& img, float gamma) { rt::save_image(path, img, gamma); }

} // namespace stage
