// encoded_output.hpp - images written through stage 08's color pipeline
// (encoding.hpp: exposure, tone map, transfer function, quantisation), in the
// formats of image_io.hpp, and the pipeline each kind of render is stored with.
// The early stages' plain path (clamp, plain gamma) keeps the names without
// "_encoded" (image_io.hpp): the two give different bytes, so they differ in name.
//
//     rt::save_image_encoded("out.png", pixels, rt::encoding{});   // sRGB, clamp tone map
//     rt::save_image_encoded("depth.png", pixels, rt::output_encoding(rt::aov_kind::depth, rt::encoding{}, pixels));
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "aov.hpp"
#include "../system/atomic_file.hpp"
#include "encoding.hpp"
#include "../core/image.hpp"
#include "image_io.hpp"

namespace rt {

/// Binary PPM of the image through the color pipeline (encoding.hpp). The
/// file is written by stage 02's write_ppm (image_io.hpp), the one PPM writer:
/// it is given the pipeline's bytes b as the levels b / 255 with gamma 1, and
/// stores each as quantize(b / 255) = b again (the level is a byte level, so
/// rounding to the nearest one gives it back exactly).
inline void write_ppm_encoded(std::ostream& out, const image& img, const encoding& enc)
{
    const std::vector<std::uint8_t> bytes = encode_image(img, enc);
    image levels(img.width, img.height);
    for (std::size_t k = 0; k < levels.pixels.size(); ++k)
        for (int channel = 0; channel < 3; ++channel)
            levels.pixels[k][channel] = float(bytes[k * 3 + std::size_t(channel)]) / 255.0f;
    write_ppm(out, levels, 1.0f);
}

/// What save_image_encoded(path, img, enc) writes, as an output_file; `img` must outlive the write.
inline output_file image_file_encoded(const std::filesystem::path& path, const image& img, const encoding& enc)
{
    const image* pixels = &img;
    return detail::image_file_by_extension(
        path, img, [pixels, enc](std::ostream& out) { write_ppm_encoded(out, *pixels, enc); },
        [pixels, enc] { return encode_image(*pixels, enc); });
}

/// Writes the image to `path`, atomically: .png and .ppm through the color
/// pipeline `enc` (exposure, tone map, transfer, quantisation), .pfm linear and exact.
inline void save_image_encoded(const std::filesystem::path& path, const image& img, const encoding& enc)
{
    const output_file file = image_file_encoded(path, img, enc);
    write_atomically(file.target, file.write);
}

/// How `pixels`, an image of `aov`, is stored in 8 bits (PNG, PPM; PFM keeps
/// the floats as they are): the shaded image through `shaded`; an AOV is data,
/// not light, so it is stored without tone map or transfer curve (clamp, linear
/// bytes). Distances are not in [0, 1], so the depth image is scaled by the
/// image's own farthest hit: 0 (black) at the eye, 255 at the farthest point.
inline encoding output_encoding(aov_kind aov, const encoding& shaded, const image& pixels)
{
    if (aov == aov_kind::shaded)
        return shaded;
    encoding data{0.0f, tonemap_kind::clamp, transfer_kind::gamma, 1.0f};
    if (aov == aov_kind::depth) {
        float farthest = 0.0f;
        for (const color& c : pixels.pixels)
            if (std::isfinite(c.r))
                farthest = std::max(farthest, c.r);
        if (farthest > 0.0f)
            data.exposure = -std::log2(farthest); // scale by 2^exposure = 1 / farthest
    }
    return data;
}

} // namespace rt
