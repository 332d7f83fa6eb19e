// encoding.hpp - the color pipeline: linear radiance to stored bytes (stage 08).
//
// The course: "RGB floats internally, RGB bytes stored". Each channel of each
// pixel goes, in this order, through
//     exposure  ->  tone map  ->  transfer function  ->  quantisation
//     c 2^stops     [0,inf)->[0,1]  sRGB or gamma        round(255 v)
// (tonemap.hpp, transfer.hpp, and quantize of byte_level.hpp, written in stage 02). Quantisation rounds to the
// nearest of the 256 levels k / 255, so every level is reached exactly and the
// error is at most half a level.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "../core/byte_level.hpp"
#include "encoding_settings.hpp" // rt::encoding, the pipeline's settings
#include "../core/error.hpp" // rt::exercise_not_done, thrown by the student kit's unfinished exercises
#include "../core/image.hpp"
#include "tonemap.hpp"
#include "transfer.hpp"
#include "../core/vec.hpp"

namespace rt {

/// One linear channel through the whole pipeline, to its display value in [0, 1] (before quantising).
inline float encode_channel(float linear, const encoding& enc)
{
    const float exposed = linear * std::exp2(enc.exposure);
    const float mapped = apply_tonemap(exposed, enc.tonemap);
    return enc.transfer == transfer_kind::srgb ? srgb_encode(mapped) : gamma_encode(mapped, enc.gamma);
}

/// One linear color to its three stored bytes.
inline std::array<std::uint8_t, 3> encode_color(const color& linear, const encoding& enc)
{
    return {quantize(encode_channel(linear.r, enc)), quantize(encode_channel(linear.g, enc)),
            quantize(encode_channel(linear.b, enc))};
}

/// The image as 8-bit RGB bytes through the pipeline, top row first (3 bytes a pixel).
inline std::vector<std::uint8_t> encode_image(const image& img, const encoding& enc)
{
    std::vector<std::uint8_t> bytes;
    bytes.reserve(img.pixels.size() * 3);
    for (const color& c : img.pixels) {
        const std::array<std::uint8_t, 3> rgb = encode_color(c, enc);
        bytes.insert(bytes.end(), rgb.begin(), rgb.end());
    }
    return bytes;
}

} // namespace rt
