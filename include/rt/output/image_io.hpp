// image_io.hpp - store an image: 8-bit PPM and PNG, and float PFM.
//
// The course: "RGB floats internally, RGB bytes stored". Two ways to bytes:
//  - the plain one of the early stages (to_byte, to_rgb8, write_ppm with a
//    gamma): clamp each linear channel to [0, 1], encode with a plain gamma,
//    quantise to 8 bits. It needs nothing from stage 08, so stage programs 02-07
//    can save images before the student has written the color pipeline.
//  - the color pipeline of stage 08 (encoded_output.hpp and encoding.hpp: exposure, tone map, sRGB or
//    gamma, quantisation): write_ppm_encoded, image_file_encoded and
//    save_image_encoded, which take an rt::encoding.
// PFM keeps the linear floats exactly (no exposure, no tone map), for depth and
// normal buffers, for comparisons and for merging. Every writer goes through
// write_atomically (atomic_file.hpp).
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "../system/atomic_file.hpp"
#include "../detail/stb_png.hpp"
#include "../core/byte_level.hpp"
#include "../core/error.hpp"
#include "../core/image.hpp"
#include "../system/path_text.hpp"

namespace rt {

/// One linear channel to a byte, the early stages' plain path: encode with a
/// plain gamma (value^(1/gamma)), then quantize (byte_level.hpp, stage 02),
/// which stores NaN and what is below 0 as 0 and what is above 1 as 255.
inline std::uint8_t to_byte(float linear, float gamma = 2.2f)
{
    // a negative value has no real power: it is stored as 0, as quantize stores it
    return quantize(linear > 0.0f ? std::pow(linear, 1.0f / gamma) : 0.0f);
}

/// The image as 8-bit RGB bytes, top row first (3 bytes a pixel).
inline std::vector<std::uint8_t> to_rgb8(const image& img, float gamma = 2.2f)
{
    std::vector<std::uint8_t> bytes;
    bytes.reserve(img.pixels.size() * 3);
    for (const color& c : img.pixels)
        for (int channel = 0; channel < 3; ++channel)
            bytes.push_back(to_byte(c[channel], gamma));
    return bytes;
}

/// Binary PPM (P6, netpbm.sourceforge.net/doc/ppm.html): the header
/// "P6\n<width> <height>\n255\n", then 3 bytes per pixel, top row first.
inline void write_ppm(std::ostream& out, const image& img, float gamma = 2.2f)
{
    // RT_EXERCISE_BEGIN(stage02: write a PPM image)
    out << "P6\n" << img.width << ' ' << img.height << "\n255\n";
    const std::vector<std::uint8_t> bytes = to_rgb8(img, gamma);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    // RT_EXERCISE_END
}

/// PNG bytes of 8-bit RGB pixels, through the vendored stb_image_write.
inline std::vector<std::uint8_t> encode_png(int width, int height, const std::vector<std::uint8_t>& rgb8)
{
    std::vector<std::uint8_t> png;
    auto append = [](void* context, void* data, int size) {
        auto* target = static_cast<std::vector<std::uint8_t>*>(context);
        const auto* first = static_cast<const std::uint8_t*>(data);
        target->insert(target->end(), first, first + size);
    };
    if (!stbi_write_png_to_func(append, &png, width, height, 3, rgb8.data(), width * 3))
        throw error("PNG encoding failed for a " + std::to_string(width) + "x" + std::to_string(height) + " image");
    return png;
}

/// Portable float map (PFM, "PF" color): the header "PF\n<w> <h>\n-1\n" (a
/// negative scale means little-endian), then 3 floats per pixel, BOTTOM row first.
inline void write_pfm(std::ostream& out, const image& img)
{
    out << "PF\n" << img.width << ' ' << img.height << "\n-1\n";
    std::vector<unsigned char> row(std::size_t(img.width) * 12);
    for (int y = img.height - 1; y >= 0; --y) {
        for (int x = 0; x < img.width; ++x) {
            const color& c = img.at(x, y);
            for (int channel = 0; channel < 3; ++channel) {
                std::uint32_t bits;
                const float value = c[channel];
                std::memcpy(&bits, &value, sizeof bits);
                unsigned char* slot = &row[(std::size_t(x) * 3 + std::size_t(channel)) * 4];
                for (int k = 0; k < 4; ++k)
                    slot[k] = static_cast<unsigned char>((bits >> (8 * k)) & 0xffu);
            }
        }
        out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size()));
    }
}

/// Reads a color PFM written by write_pfm (or any little- or big-endian "PF").
inline image read_pfm(std::istream& in, const std::string& name = "<pfm>")
{
    std::string magic;
    int width = 0, height = 0;
    double scale = 0;
    if (!(in >> magic >> width >> height >> scale) || magic != "PF" || width <= 0 || height <= 0 ||
        scale == 0 || std::int64_t(width) * height > (std::int64_t(1) << 28))
        throw make_error(source_location{name, 1, 1}, "a color PFM header 'PF width height scale'",
                         "something else", "is this a PFM file written by rt?");
    in.get(); // the single whitespace byte after the scale
    const bool little = scale < 0;
    // Read the pixel bytes before allocating the image, in chunks, so that a
    // header that claims more pixels than the file holds costs no more memory
    // than the file (a 30-byte file could otherwise ask for 3 GB).
    const std::size_t row_size = std::size_t(width) * 12;
    const std::size_t total = row_size * std::size_t(height);
    std::vector<unsigned char> bytes;
    std::vector<char> chunk(std::size_t(1) << 16);
    while (bytes.size() < total) {
        const std::size_t wanted = std::min(chunk.size(), total - bytes.size());
        in.read(chunk.data(), std::streamsize(wanted));
        bytes.insert(bytes.end(), chunk.begin(), chunk.begin() + in.gcount());
        if (std::size_t(in.gcount()) < wanted)
            throw error(source_location{name}, "expected " + std::to_string(width) + "x" +
                                                   std::to_string(height) + " pixels, found a truncated file");
    }
    image img(width, height);
    for (int y = height - 1; y >= 0; --y) {
        const unsigned char* row = &bytes[std::size_t(height - 1 - y) * row_size];
        for (int x = 0; x < width; ++x)
            for (int channel = 0; channel < 3; ++channel) {
                const unsigned char* slot = &row[(std::size_t(x) * 3 + std::size_t(channel)) * 4];
                std::uint32_t bits = 0;
                for (int k = 0; k < 4; ++k)
                    bits |= std::uint32_t(slot[little ? k : 3 - k]) << (8 * k);
                float value;
                std::memcpy(&value, &bits, sizeof value);
                img.at(x, y)[channel] = value;
            }
    }
    return img;
}

/// The lower-case extension of `path` (".png", ".ppm" or ".pfm"), or an error naming the formats.
inline std::string image_format_of(const std::filesystem::path& path)
{
    std::string extension = detail::utf8_text(path.extension());
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (extension != ".ppm" && extension != ".pfm" && extension != ".png")
        throw error(source_location{detail::utf8_text(path)},
                    "expected an image extension .png, .ppm or .pfm, found '" + extension +
                        "'; name the output file with one of them");
    return extension;
}

/// Throws the error save_image would throw for `path`'s extension, unless it is
/// one save_image writes (.png, .ppm, .pfm, in any case).
inline void check_image_path(const std::filesystem::path& path) { image_format_of(path); }

/// Throws rt::error unless `path` names an image format rt writes and a file
/// can be created there: call it before a long render, not after.
inline void check_image_output(const std::filesystem::path& path)
{
    image_format_of(path);
    check_writable(path);
}

namespace detail {

/// The output_file that writes `img` to `path` in the format its extension
/// names; `write_8bit_ppm(out)` and `rgb8()` give the 8-bit encodings, PFM is
/// written linear. The writers are called later, by write_atomically or
/// write_all_atomically, so `img` must outlive that call.
template <class PpmWriter, class Rgb8>
output_file image_file_by_extension(const std::filesystem::path& path, const image& img, PpmWriter write_8bit_ppm,
                                    Rgb8 rgb8)
{
    const std::string extension = image_format_of(path);
    const image* pixels = &img;
    if (extension == ".ppm")
        return output_file{path, write_8bit_ppm};
    if (extension == ".pfm")
        return output_file{path, [pixels](std::ostream& out) { write_pfm(out, *pixels); }};
    return output_file{path, [pixels, rgb8](std::ostream& out) {
                           const std::vector<std::uint8_t> png = encode_png(pixels->width, pixels->height, rgb8());
                           out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
                       }};
}

} // namespace detail

/// What save_image(path, img, gamma) writes, as an output_file for
/// write_all_atomically (several images all or none); `img` must outlive the write.
inline output_file image_file(const std::filesystem::path& path, const image& img, float gamma = 2.2f)
{
    const image* pixels = &img;
    return detail::image_file_by_extension(
        path, img, [pixels, gamma](std::ostream& out) { write_ppm(out, *pixels, gamma); },
        [pixels, gamma] { return to_rgb8(*pixels, gamma); });
}

/// Writes the image to `path`, atomically, in the format its extension names:
/// .png and .ppm (8-bit: clamped, plain gamma, see to_byte) or .pfm (linear floats).
/// This is the early stages' writer; stage 08's is save_image_encoded (encoded_output.hpp).
inline void save_image(const std::filesystem::path& path, const image& img, float gamma = 2.2f)
{
    const output_file file = image_file(path, img, gamma);
    write_atomically(file.target, file.write);
}

} // namespace rt
