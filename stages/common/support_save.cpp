// The image writer for the stage programs, compiled once (support.hpp).
#include "support.hpp"

#include <rt/output/image_io.hpp>

#include "command_line.hpp" // file_argument

namespace stage {

void save_image(const std::string& path, const rt::image& img, float gamma)
{
    rt::save_image(file_argument(path), img, gamma);
}

void save_images(const std::vector<image_output>& outputs)
{
    std::vector<rt::output_file> files;
    for (const image_output& o : outputs)
        files.push_back(rt::image_file(file_argument(o.path), *o.pixels, o.gamma));
    rt::write_all_atomically(files);
}

void check_image_output(const std::string& path) { rt::check_image_output(file_argument(path)); }

std::string stored_bytes(const rt::color& c, float gamma)
{
    return std::to_string(rt::to_byte(c.r, gamma)) + " " + std::to_string(rt::to_byte(c.g, gamma)) + " " +
           std::to_string(rt::to_byte(c.b, gamma));
}

} // namespace stage
