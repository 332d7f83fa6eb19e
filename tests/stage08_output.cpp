// Stage 08 - output: tone map, gamma, store; and the renderer that produces
// what is stored (samplers, reconstruction filters, tiles and threads).
//
// Expected values are closed forms worked out by hand in each case (the
// formulas and their sources are in the headers: tonemap.hpp, transfer.hpp,
// encoding.hpp, random.hpp, sampler.hpp, filter.hpp). The renderer is tested
// with hand-made ray sources and analytic radiance functions (a constant, a
// half-plane, a function of the film position), never with another stage's
// code, so these cases test stage 08 alone.
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

#include <rt/atomic_file.hpp>
#include <rt/encoding.hpp>
#include <rt/error.hpp>
#include <rt/filter.hpp>
#include <rt/image.hpp>
#include <rt/encoded_output.hpp>
#include <rt/image_io.hpp>
#include <rt/progress.hpp>
#include <rt/random.hpp>
#include <rt/ray.hpp>
#include <rt/aov.hpp>
#include <rt/renderer.hpp>
#include <rt/sampler.hpp>
#include <rt/tonemap.hpp>
#include <rt/transfer.hpp>

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

TEST_CASE("clamp tone map: identity on [0, 1], 0 below, 1 above, NaN to 0")
{
    INFO("expected T(x) = x on [0, 1], 1 above (inf too), 0 below and for NaN (write !(x > 0) to catch NaN)");
    CHECK(rt::tonemap_clamp(0.0f) == 0.0f);
    CHECK(rt::tonemap_clamp(0.25f) == 0.25f);
    CHECK(rt::tonemap_clamp(1.0f) == 1.0f);
    CHECK(rt::tonemap_clamp(7.5f) == 1.0f);
    CHECK(rt::tonemap_clamp(-2.0f) == 0.0f);
    CHECK(rt::tonemap_clamp(std::numeric_limits<float>::infinity()) == 1.0f);
    CHECK(rt::tonemap_clamp(std::nanf("")) == 0.0f);
}

TEST_CASE("Reinhard tone map x / (1 + x) at known points")
{
    {
        INFO("expected T(x) = x / (1 + x): T(0) = 0, T(1) = 1/2, T(3) = 3/4, T(1/4) = 1/5, T(99) = 0.99");
        CHECK(rt::tonemap_reinhard(0.0f) == 0.0f);
        CHECK(rt::tonemap_reinhard(1.0f) == doctest::Approx(0.5));  // 1 / 2
        CHECK(rt::tonemap_reinhard(3.0f) == doctest::Approx(0.75)); // 3 / 4
        CHECK(rt::tonemap_reinhard(0.25f) == doctest::Approx(0.2)); // (1/4) / (5/4)
        CHECK(rt::tonemap_reinhard(99.0f) == doctest::Approx(0.99));
    }
    CHECK_MESSAGE(rt::tonemap_reinhard(std::numeric_limits<float>::infinity()) == 1.0f,
                  "expected T(inf) = 1, the limit of x / (1 + x); computed as written, inf / inf is NaN (a black pixel): "
                  "return 1 for an infinite x");
    CHECK_MESSAGE(rt::tonemap_reinhard(-1.0f) == 0.0f, "expected 0 for x <= 0 (no negative light); x / (1 + x) at -1 divides by 0");
    CHECK_MESSAGE(rt::tonemap_reinhard(std::nanf("")) == 0.0f, "expected 0 for a NaN sample (a black pixel, not NaN bytes)");
    // increasing and below 1 everywhere
    float previous = 0;
    for (float x = 0.01f; x < 1000; x *= 1.1f) {
        const float t = rt::tonemap_reinhard(x);
        CAPTURE(x);
        REQUIRE_MESSAGE(t > previous, "expected T increasing: T(x) = " << t << " after " << previous);
        REQUIRE_MESSAGE(t < 1.0f, "expected T(x) < 1 for every finite x, found " << t);
        previous = t;
    }
}

TEST_CASE("the naive x / (1 + x) turns an infinite sample into a black pixel, the tone map does not")
{
    // a single overflowing sample (inf radiance) must come out white, not black
    const float inf = std::numeric_limits<float>::infinity();
    const float naive = inf / (1.0f + inf);
    CHECK_MESSAGE(std::isnan(naive), "expected inf / (1 + inf) = inf / inf to be NaN (IEEE 754)");
    CHECK_MESSAGE(int(rt::quantize(rt::srgb_encode(naive))) == 0,
                  "expected a NaN sample stored as 0, a black pixel (srgb_encode and quantize send NaN to 0)");
    CHECK_MESSAGE(int(rt::quantize(rt::srgb_encode(rt::tonemap_reinhard(inf)))) == 255,
                  "expected an infinite sample stored as 255, white: tonemap_reinhard(inf) must be the limit 1, "
                  "not inf / inf = NaN (found tonemap_reinhard(inf) = " << rt::tonemap_reinhard(inf) << ")");
}

TEST_CASE("ACES filmic fit: T(1) = 2.54 / 3.16, reaches 1 at x = 7.24 and stays there")
{
    // T(x) = x(2.51 x + 0.03) / (x(2.43 x + 0.59) + 0.14)
    INFO("expected Narkowicz's fit T(x) = x(2.51 x + 0.03) / (x(2.43 x + 0.59) + 0.14), clamped to [0, 1]: T(0) = 0, "
         "T(1) = 2.54 / 3.16, 1 from x = 7.2417 on (inf too), 0 for x < 0 and NaN, increasing below 7.24");
    CHECK(rt::tonemap_aces(0.0f) == 0.0f);
    CHECK(rt::tonemap_aces(1.0f) == doctest::Approx(2.54 / 3.16)); // 0.8038: "1 maps to about 0.8"
    // T(x) = 1 where 0.08 x^2 - 0.56 x - 0.14 = 0: x = (0.56 + sqrt(0.56^2 + 4 * 0.08 * 0.14)) / 0.16
    const double x_one = (0.56 + std::sqrt(0.56 * 0.56 + 4 * 0.08 * 0.14)) / 0.16;
    CHECK(x_one == doctest::Approx(7.2417).epsilon(1e-4));
    CHECK(rt::tonemap_aces(float(x_one) * 0.98f) < 1.0f);
    CHECK(rt::tonemap_aces(float(x_one) * 1.02f) == 1.0f);
    CHECK(rt::tonemap_aces(1e30f) == 1.0f);
    CHECK(rt::tonemap_aces(std::numeric_limits<float>::infinity()) == 1.0f);
    CHECK(rt::tonemap_aces(-3.0f) == 0.0f);
    CHECK(rt::tonemap_aces(std::nanf("")) == 0.0f);
    float previous = 0;
    for (float x = 0.01f; x < 7.0f; x += 0.01f) {
        const float t = rt::tonemap_aces(x);
        CAPTURE(x);
        REQUIRE(t > previous);
        previous = t;
    }
}

TEST_CASE("sRGB encode at known points (IEC 61966-2-1)")
{
    INFO("expected V = 12.92 x for x <= 0.0031308, else 1.055 x^(1/2.4) - 0.055 (IEC 61966-2-1), increasing, with "
         "srgb_decode its inverse");
    CHECK(rt::srgb_encode(0.0f) == 0.0f);
    CHECK(rt::srgb_encode(1.0f) == doctest::Approx(1.0).epsilon(1e-6)); // 1.055 - 0.055
    // 1.055 * 0.5^(1/2.4) - 0.055
    CHECK(rt::srgb_encode(0.5f) == doctest::Approx(1.055 * std::pow(0.5, 1 / 2.4) - 0.055).epsilon(1e-6));
    CHECK(rt::srgb_encode(0.5f) == doctest::Approx(0.7353570).epsilon(1e-6));
    // the linear segment: slope 12.92 below the threshold
    CHECK(rt::srgb_encode(0.001f) == doctest::Approx(0.01292).epsilon(1e-6));
    CHECK(rt::srgb_encode(0.002f) == doctest::Approx(0.02584).epsilon(1e-6));
    // the two pieces meet at 0.0031308: 12.92 x = 0.04044994 and the power piece 0.04044991
    const float x0 = 0.0031308f;
    const float below = rt::srgb_encode(std::nextafter(x0, 0.0f));
    const float above = rt::srgb_encode(std::nextafter(x0, 1.0f));
    CHECK(below == doctest::Approx(0.0404499).epsilon(1e-5));
    CHECK(std::fabs(above - below) < 1e-6f);
    // increasing, and decode inverts it
    float previous = -1;
    for (int k = 0; k <= 1000; ++k) {
        const float x = float(k) / 1000;
        const float v = rt::srgb_encode(x);
        CAPTURE(x);
        REQUIRE(v > previous);
        REQUIRE(rt::srgb_decode(v) == doctest::Approx(x).epsilon(1e-5).scale(1e-3));
        previous = v;
    }
    // the decode side's own known point: v = 0.04045 is x = 0.04045 / 12.92
    CHECK(rt::srgb_decode(0.04045f) == doctest::Approx(0.04045 / 12.92).epsilon(1e-6));
}

TEST_CASE("a plain gamma 2.2 is not sRGB: up to 9 byte levels apart in the shadows")
{
    // by hand: x = 0.001 gives sRGB 12.92 x = 0.01292 -> byte 3, but
    // 0.001^(1/2.2) = 0.0433 -> byte 11; at mid-grey 0.18 the two are 118 and 117
    INFO("by hand: x = 0.001 is byte 3 in sRGB (12.92 x = 0.01292) and 11 with gamma 2.2 (x^(1/2.2) = 0.0433); "
         "x = 0.18 is 118 and 117");
    CHECK(int(rt::quantize(rt::srgb_encode(0.001f))) == 3);
    CHECK(int(rt::quantize(rt::gamma_encode(0.001f, 2.2f))) == 11);
    CHECK(int(rt::quantize(rt::srgb_encode(0.18f))) == 118);
    CHECK(int(rt::quantize(rt::gamma_encode(0.18f, 2.2f))) == 117);
    int worst = 0;
    float worst_x = 0;
    int worst_above_tenth = 0;
    for (int k = 0; k <= 100000; ++k) {
        const float x = float(k) / 100000;
        const int d = std::abs(int(rt::quantize(rt::gamma_encode(x, 2.2f))) - int(rt::quantize(rt::srgb_encode(x))));
        if (d > worst) {
            worst = d;
            worst_x = x;
        }
        if (x >= 0.1f)
            worst_above_tenth = std::max(worst_above_tenth, d);
    }
    CAPTURE(worst_x);
    INFO("expected the two encodings at most 9 byte levels apart, that worst near x = 0.0013 (sRGB's linear "
         "segment), and at most 2 apart above x = 0.1; found " << worst << " and " << worst_above_tenth);
    CHECK(worst == 9);           // near x = 0.0013, where sRGB is still on its linear segment
    CHECK(worst_x < 0.003f);
    CHECK(worst_above_tenth <= 2);
}

TEST_CASE("the pipeline runs exposure, tone map, transfer, quantisation in that order")
{
    rt::encoding enc;
    enc.exposure = 1;
    enc.tonemap = rt::tonemap_kind::reinhard;
    enc.transfer = rt::transfer_kind::srgb;
    // 0.5 * 2^1 = 1 -> Reinhard 1/2 -> sRGB 0.7353570 -> 255 * 0.7353570 = 187.52 -> 188
    INFO("expected exposure first (x 2^exposure), then the tone map, then the transfer curve, then quantisation: "
         "0.5 at exposure 1 is 1, Reinhard 1/2, sRGB 0.7353570, byte 188; 0 stays 0; 1e9 is byte 255");
    CHECK(rt::encode_channel(0.5f, enc) == doctest::Approx(0.7353570).epsilon(1e-6));
    const auto bytes = rt::encode_color(rt::color(0.5f, 0.0f, 1e9f), enc);
    CHECK(int(bytes[0]) == 188);
    CHECK(int(bytes[1]) == 0);
    CHECK(int(bytes[2]) == 255);
    // clamp + gamma 2: 0.125 * 2^1 = 0.25 -> sqrt = 0.5 -> 128
    rt::encoding plain;
    plain.exposure = 1;
    plain.transfer = rt::transfer_kind::gamma;
    plain.gamma = 2;
    CHECK(int(rt::encode_color(rt::color(0.125f), plain)[0]) == 128);
    // ACES with exposure -1: 2 * 2^-1 = 1 -> 2.54/3.16 = 0.80380 -> sRGB: 1.055 * 0.80380^(1/2.4) - 0.055
    rt::encoding filmic;
    filmic.exposure = -1;
    filmic.tonemap = rt::tonemap_kind::aces;
    CHECK(rt::encode_channel(2.0f, filmic) == doctest::Approx(1.055 * std::pow(2.54 / 3.16, 1 / 2.4) - 0.055).epsilon(1e-5));
}

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

// ===========================================================================
// storing: PPM and PNG through the pipeline, PFM exact, atomic writes

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
    rt::write_ppm(out, img, enc);
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

TEST_CASE("save_image with an encoding: .ppm holds the pipeline's bytes, .png is a PNG, .pfm is linear")
{
    scratch_folder folder("save");
    rt::image img(3, 1);
    img.at(0, 0) = {0.2f, 0.4f, 0.6f};
    img.at(1, 0) = {5.0f, 0.0f, 0.01f};
    img.at(2, 0) = {-0.5f, 1.0f, 0.7f};
    rt::encoding enc;
    enc.exposure = 0.5f;
    enc.tonemap = rt::tonemap_kind::aces;
    rt::save_image(folder.path / "a.ppm", img, enc);
    rt::save_image(folder.path / "a.png", img, enc);
    rt::save_image(folder.path / "a.pfm", img, enc);

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

// ===========================================================================
// random numbers and samplers

// ===========================================================================
// reconstruction filters

// ===========================================================================
// the renderer

namespace {

} // namespace

