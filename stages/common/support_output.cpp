// Stage 08's encoded output, compiled once (support_frame.hpp): the one support
// file that includes the stage-08 exercises (encoding.hpp).
#include "support_frame.hpp"

#include <rt/encoded_output.hpp>

namespace stage {

void save_encoded(const std::string& path, const rt::image& img, rt::aov_kind aov, const rt::encoding& enc)
{
    rt::save_image(path, img, rt::output_encoding(aov, enc, img));
}

} // namespace stage
