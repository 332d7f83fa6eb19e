// Stage 08's encoded output, compiled once (support_frame.hpp): the one support
// file that includes the stage-08 exercises (encoding.hpp).
#include "support_frame.hpp"

#include <array>
#include <cstdint>
#include <string>

#include <rt/output/encoded_output.hpp>
#include <rt/output/encoding.hpp>
#include <rt/output/tonemap.hpp>

#include "command_line.hpp"     // file_argument
#include "render_arguments.hpp" // number_text

namespace stage {

void save_encoded(const std::string& path, const rt::image& img, rt::aov_kind aov, const rt::encoding& enc)
{
    rt::save_image_encoded(file_argument(path), img, rt::output_encoding(aov, enc, img));
}

void add_encoding_story(story& st, const rt::encoding& enc, int samples_per_pixel)
{
    const rt::color exposed = rt::apply_exposure(st.linear, enc.exposure);
    const rt::color mapped = rt::apply_tonemap(exposed, enc.tonemap);
    const std::array<std::uint8_t, 3> bytes = rt::encode_color(st.linear, enc);
    auto text = [](const rt::color& c) {
        return number_text(double(c.r)) + " " + number_text(double(c.g)) + " " + number_text(double(c.b));
    };
    st.values.push_back(
        {"samples:", std::to_string(samples_per_pixel) + " per pixel in the image; this story follows the ray through the centre"});
    st.values.push_back({"exposed (2^" + number_text(double(enc.exposure)) + "):", text(exposed)});
    st.values.push_back({std::string("tone mapped (") + rt::name_of(enc.tonemap) + "):", text(mapped)});
    st.values.push_back({std::string("stored bytes (") +
                             (enc.transfer == rt::transfer_kind::srgb ? std::string("sRGB")
                                                                      : "gamma " + number_text(double(enc.gamma))) +
                             "):",
                         std::to_string(bytes[0]) + " " + std::to_string(bytes[1]) + " " + std::to_string(bytes[2])});
}

} // namespace stage
