// library_image_output.cpp - the parts of stage 08's output that are library
// code, not exercises: exposure, AOVs in 8 bits, the names of tone maps,
// samplers and filters, PFM files, and atomic writes (include/rt/output/image_io.hpp,
// include/rt/system/atomic_file.hpp). Expected values are closed forms worked out by
// hand in each case. No exercise is called.
#include "rt_doctest.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <rt/system/atomic_file.hpp>
#include <rt/output/encoding.hpp>
#include <rt/core/error.hpp>
#include <rt/rendering/filter.hpp>
#include <rt/core/image.hpp>
#include <rt/output/encoded_output.hpp>
#include <rt/output/image_io.hpp>
#include <rt/rendering/progress.hpp>
#include <rt/core/random.hpp>
#include <rt/core/ray.hpp>
#include <rt/output/aov.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/rendering/sampler.hpp>
#include <rt/output/tonemap.hpp>
#include <rt/output/transfer.hpp>

namespace {

// ---------------------------------------------------------------------------
// helpers

/// A folder of its own under the system's temporary folder, removed at the end.
struct scratch_folder {
    std::filesystem::path path;
    explicit scratch_folder(const std::string& name)
    {
        rt::pcg32 rng(std::uint64_t(std::chrono::steady_clock::now().time_since_epoch().count()), 7);
        path = std::filesystem::temp_directory_path() / ("rt-stage08-" + name + "-" + std::to_string(rng.next_u32()));
        std::filesystem::create_directories(path);
    }
    ~scratch_folder()
    {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    scratch_folder(const scratch_folder&) = delete;
    scratch_folder& operator=(const scratch_folder&) = delete;
};

std::uint32_t bits_of(float value)
{
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

std::string read_all(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Two images are equal bit for bit (also telling -0 from 0 and NaN payloads apart).
bool identical(const rt::image& a, const rt::image& b)
{
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(rt::color)) == 0;
}

} // namespace

// ===========================================================================
// tone maps, exposure, transfer functions, quantisation
//
// The 8-bit store of stage 08's pipeline: bytes are quantize (stage 02) of
// encode_channel (stage 08), so these cases need both stages and live here,
// where the grader does not score them; stage 08's own suite checks
// encode_channel's values.

TEST_CASE("the pipeline with clamp and a plain gamma gives the early stages' bytes (to_byte)")
{
    for (float gamma : {1.0f, 2.0f, 2.2f}) {
        rt::encoding enc;
        enc.tonemap = rt::tonemap_kind::clamp;
        enc.transfer = rt::transfer_kind::gamma;
        enc.gamma = gamma;
        for (int k = -20; k <= 1100; ++k) {
            const float x = float(k) / 1000;
            CAPTURE(x);
            CHECK(rt::encode_color(rt::color(x), enc)[0] == rt::to_byte(x, gamma));
        }
    }
}

TEST_CASE("PPM through the pipeline: the header, then the pipeline's bytes, top row first")
{
    rt::image img(2, 2);
    img.at(0, 0) = {0.5f, 0.0f, 1.0f};
    img.at(1, 0) = {2.0f, 0.25f, -1.0f};
    img.at(0, 1) = {0.0031308f, 0.1f, 0.9f};
    img.at(1, 1) = {1e6f, std::nanf(""), 0.5f};
    rt::encoding enc;
    enc.tonemap = rt::tonemap_kind::reinhard;
    std::ostringstream out;
    rt::write_ppm_encoded(out, img, enc);
    const std::string bytes = out.str();
    const std::string header = "P6\n2 2\n255\n";
    REQUIRE(bytes.size() == header.size() + 12);
    CHECK(bytes.substr(0, header.size()) == header);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x)
            for (int channel = 0; channel < 3; ++channel) {
                // each byte is quantize(sRGB(x / (1 + x))) of its channel
                const float linear = img.at(x, y)[channel];
                const float mapped = linear > 0 ? linear / (1 + linear) : 0.0f;
                const int expected = int(rt::quantize(rt::srgb_encode(mapped)));
                CHECK(int(std::uint8_t(bytes[header.size() + std::size_t((y * 2 + x) * 3 + channel)])) == expected);
            }
    // the hand-worked ones: 0.5 -> 1/3 -> sRGB 1.055 (1/3)^(1/2.4) - 0.055 = 0.6120 -> 156
    CHECK(int(std::uint8_t(bytes[header.size()])) == int(255 * (1.055 * std::pow(1.0 / 3, 1 / 2.4) - 0.055) + 0.5));
}

TEST_CASE("PPM through the pipeline: each of the 256 byte levels is stored as the pipeline gives it")
{
    // clamp, a plain gamma of 1 and no exposure store the linear level k / 255 as
    // the byte k (round(255 k / 255)); the PPM must hold exactly those bytes
    rt::encoding enc;
    enc.tonemap = rt::tonemap_kind::clamp;
    enc.transfer = rt::transfer_kind::gamma;
    enc.gamma = 1.0f;
    rt::image img(256, 1);
    for (int k = 0; k < 256; ++k)
        img.at(k, 0) = rt::color(float(k) / 255.0f, float(255 - k) / 255.0f, float(k) / 255.0f);
    std::ostringstream out;
    rt::write_ppm_encoded(out, img, enc);
    const std::string bytes = out.str();
    const std::string header = "P6\n256 1\n255\n";
    REQUIRE(bytes.size() == header.size() + 256 * 3);
    CHECK(bytes.substr(0, header.size()) == header);
    const std::vector<std::uint8_t> expected = rt::encode_image(img, enc);
    for (int k = 0; k < 256; ++k) {
        CAPTURE(k);
        for (int channel = 0; channel < 3; ++channel) {
            const std::size_t at = std::size_t(k) * 3 + std::size_t(channel);
            CHECK(int(std::uint8_t(bytes[header.size() + at])) == int(expected[at]));
        }
        CHECK(int(std::uint8_t(bytes[header.size() + std::size_t(k) * 3])) == k);
    }
}

TEST_CASE("save_image_encoded: .ppm holds the pipeline's bytes, .png is a PNG, .pfm is linear")
{
    scratch_folder folder("save");
    rt::image img(3, 1);
    img.at(0, 0) = {0.2f, 0.4f, 0.6f};
    img.at(1, 0) = {5.0f, 0.0f, 0.01f};
    img.at(2, 0) = {-0.5f, 1.0f, 0.7f};
    rt::encoding enc;
    enc.exposure = 0.5f;
    enc.tonemap = rt::tonemap_kind::aces;
    rt::save_image_encoded(folder.path / "a.ppm", img, enc);
    rt::save_image_encoded(folder.path / "a.png", img, enc);
    rt::save_image_encoded(folder.path / "a.pfm", img, enc);

    const std::string ppm = read_all(folder.path / "a.ppm");
    const std::vector<std::uint8_t> expected = rt::encode_image(img, enc);
    const std::string header = "P6\n3 1\n255\n";
    INFO("expected the .ppm to hold the header '" << "P6 3 1 255" << "' then exactly encode_image's bytes, the .png "
         "to start with the PNG signature, and the .pfm to hold the linear floats unchanged (no exposure, no tone map)");
    REQUIRE(ppm.size() == header.size() + expected.size());
    CHECK(std::equal(expected.begin(), expected.end(), ppm.begin() + std::ptrdiff_t(header.size()),
                     [](std::uint8_t a, char b) { return a == std::uint8_t(b); }));

    const std::string png = read_all(folder.path / "a.png");
    REQUIRE(png.size() > 8);
    CHECK(png.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8)); // the PNG signature

    std::ifstream pfm_in(folder.path / "a.pfm", std::ios::binary);
    const rt::image back = rt::read_pfm(pfm_in, "a.pfm");
    CHECK(identical(back, img)); // no exposure, no tone map: the linear floats
}


namespace {

} // namespace

TEST_CASE("exposure: +1 stop doubles, -1 stop halves, 0 changes nothing")
{
    const rt::color c(0.1f, 0.5f, 3.0f);
    CHECK(rt::apply_exposure(c, 1.0f) == c * 2.0f);
    CHECK(rt::apply_exposure(c, -1.0f) == c * 0.5f);
    CHECK(rt::apply_exposure(c, 0.0f) == c);
    CHECK(rt::apply_exposure(c, 3.0f).b == doctest::Approx(24.0));
}

TEST_CASE("tone map, sampler and filter names read back")
{
    for (auto kind : {rt::tonemap_kind::clamp, rt::tonemap_kind::reinhard, rt::tonemap_kind::aces})
        CHECK(rt::tonemap_from_name(rt::name_of(kind)) == kind);
    for (auto kind : {rt::sampler_kind::center, rt::sampler_kind::grid, rt::sampler_kind::random,
                      rt::sampler_kind::jittered, rt::sampler_kind::halton})
        CHECK(rt::sampler_from_name(rt::name_of(kind)) == kind);
    for (auto kind : {rt::filter_kind::box, rt::filter_kind::tent, rt::filter_kind::gaussian, rt::filter_kind::mitchell})
        CHECK(rt::filter_from_name(rt::name_of(kind)) == kind);
    CHECK_FALSE(rt::tonemap_from_name("filmic").has_value());
    CHECK_FALSE(rt::sampler_from_name("sobol").has_value());
    CHECK_FALSE(rt::filter_from_name("lanczos").has_value());
}

TEST_CASE("PFM round trip is bit-exact: negative, tiny, huge, zero, -0, infinite")
{
    const float values[] = {0.0f,
                            -0.0f,
                            1.0f,
                            -1.5f,
                            0.1f,
                            std::numeric_limits<float>::denorm_min(),  // 1.4e-45
                            -std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::min(),         // the smallest normal
                            std::numeric_limits<float>::max(),
                            -std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity(),
                            1e-30f,
                            123456.789f,
                            std::nextafter(1.0f, 2.0f),
                            3.14159265f,
                            -2.7182818f,
                            1e38f};
    const int count = int(std::size(values));
    rt::image img(5, 4); // 20 pixels, 60 channels: the values and a position-dependent rest
    for (int k = 0; k < 60; ++k)
        img.pixels[std::size_t(k / 3)][k % 3] = k < count ? values[k] : float(k) * -0.37f;
    std::stringstream buffer;
    rt::write_pfm(buffer, img);
    const rt::image back = rt::read_pfm(buffer);
    REQUIRE(back.width == 5);
    REQUIRE(back.height == 4);
    for (std::size_t k = 0; k < img.pixels.size(); ++k)
        for (int channel = 0; channel < 3; ++channel)
            CHECK(bits_of(back.pixels[k][channel]) == bits_of(img.pixels[k][channel]));

    // and through a file written by save_image_encoded
    scratch_folder folder("pfm");
    rt::save_image_encoded(folder.path / "round.pfm", img, rt::encoding{});
    std::ifstream in(folder.path / "round.pfm", std::ios::binary);
    CHECK(identical(rt::read_pfm(in, "round.pfm"), img));
}

TEST_CASE("plain gamma: x^(1/gamma), gamma 1 stores linear values")
{
    CHECK(rt::gamma_encode(0.25f, 2.0f) == doctest::Approx(0.5));
    CHECK(rt::gamma_encode(0.125f, 3.0f) == doctest::Approx(0.5));
    CHECK(rt::gamma_encode(0.3f, 1.0f) == doctest::Approx(0.3));
    CHECK(rt::gamma_encode(1.0f, 2.2f) == 1.0f);
    CHECK(rt::gamma_encode(-1.0f, 2.2f) == 0.0f);
    CHECK(rt::gamma_encode(std::nanf(""), 2.2f) == 0.0f);
}

namespace {

std::string read_file_bytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

} // namespace

TEST_CASE("AOVs are stored as data: no tone curve, and depth scaled by the image's farthest hit")
{
    // output_encoding's contract, without the stage-08 exercises: the settings it picks
    rt::image depth(4, 1);
    const float d[] = {0.0f, 1.0f, 3.0f, 4.0f};
    for (int x = 0; x < 4; ++x)
        depth.at(x, 0) = rt::color(d[x]);
    const rt::encoding shaded{3.0f, rt::tonemap_kind::aces, rt::transfer_kind::srgb, 2.2f};
    const rt::encoding enc = rt::output_encoding(rt::aov_kind::depth, shaded, depth);
    INFO("a depth image: clamp, gamma 1 and an exposure that maps the farthest hit, 4, to exactly 1");
    CHECK(enc.tonemap == rt::tonemap_kind::clamp);
    CHECK(enc.transfer == rt::transfer_kind::gamma);
    CHECK(enc.gamma == 1.0f);
    CHECK(rt::apply_exposure(rt::color(4.0f), enc.exposure).r == 1.0f);
    CHECK(rt::apply_exposure(rt::color(1.0f), enc.exposure).r == 0.25f);
    // a farthest distance that is no power of two still maps to 1 within a rounding
    depth.at(3, 0) = rt::color(3.0f);
    const float top = rt::apply_exposure(rt::color(3.0f), rt::output_encoding(rt::aov_kind::depth, shaded, depth).exposure).r;
    CHECK(top == doctest::Approx(1.0f).epsilon(1e-6));
    // normals are (n + 1) / 2 in [0, 1]: stored linearly, whatever the shaded settings
    const rt::encoding normals = rt::output_encoding(rt::aov_kind::normal, shaded, depth);
    CHECK(normals.exposure == 0.0f);
    CHECK(normals.tonemap == rt::tonemap_kind::clamp);
    CHECK(normals.gamma == 1.0f);
    // and the shaded image keeps its own settings
    CHECK(rt::output_encoding(rt::aov_kind::shaded, shaded, depth).tonemap == rt::tonemap_kind::aces);
}

TEST_CASE("atomic output: a write that fails half-way leaves the earlier file intact and nothing else")
{
    scratch_folder folder("atomic");
    const std::filesystem::path target = folder.path / "render.pfm";
    const rt::image first(2, 1, rt::color(0.5f));
    rt::save_image_encoded(target, first, rt::encoding{}); // PFM: linear, no encoding step
    const std::string before = read_file_bytes(target);
    REQUIRE(before.size() == std::string("PF\n2 1\n-1\n").size() + 2 * 3 * 4);

    // a writer that has written part of a new image when it fails
    const rt::image second(64, 64, rt::color(0.9f));
    CHECK_THROWS_AS(rt::write_atomically(target,
                                         [&](std::ostream& out) {
                                             rt::write_pfm(out, second);
                                             out.flush();
                                             throw std::runtime_error("induced failure half-way");
                                         }),
                    std::runtime_error);
    CHECK(read_file_bytes(target) == before);
    int files = 0; // no temporary file is left beside it
    for (const auto& entry : std::filesystem::directory_iterator(folder.path)) {
        CAPTURE(entry.path().string());
        ++files;
    }
    CHECK(files == 1);

    // an unwritable destination is an error before anything is written
    CHECK_THROWS_AS(rt::save_image_encoded(folder.path / "missing-folder" / "x.pfm", first, rt::encoding{}), rt::error);
    CHECK_THROWS_AS(rt::save_image_encoded(folder.path, first, rt::encoding{}), rt::error); // a folder, not a file
    CHECK_THROWS_AS(rt::save_image_encoded(folder.path / "x.jpg", first, rt::encoding{}), rt::error);
    CHECK_THROWS_AS(rt::check_image_output(folder.path / "x.jpg"), rt::error); // checked before rendering
    CHECK_THROWS_AS(rt::check_image_output(folder.path / "missing-folder" / "x.png"), rt::error);
    CHECK_NOTHROW(rt::check_image_output(folder.path / "next.PNG"));
    CHECK(read_file_bytes(target) == before);
}
