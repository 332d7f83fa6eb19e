// Stage 08 - output: tone map, gamma, store; and the renderer that produces
// what is stored (samplers, reconstruction filters, tiles and threads).
//
// Expected values are closed forms worked out by hand in each case (the
// formulas and their sources are in the headers: tonemap.hpp, transfer.hpp,
// encoding.hpp, random.hpp, sampler.hpp, filter.hpp). The renderer is tested
// with hand-made ray sources and analytic radiance functions (a constant, a
// half-plane, a function of the film position), never with another stage's
// code, so these cases test stage 08 alone.
#include <doctest/doctest.h>

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
#include <rt/image_io.hpp>
#include <rt/progress.hpp>
#include <rt/random.hpp>
#include <rt/ray.hpp>
#include <rt/render_setup.hpp>
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

std::uint32_t bits_of(float value)
{
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

/// Two images are equal bit for bit (also telling -0 from 0 and NaN payloads apart).
bool identical(const rt::image& a, const rt::image& b)
{
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(rt::color)) == 0;
}

/// The ray source of the renderer tests: an orthographic "camera" whose ray
/// through film position (x, y) starts at (x, y, 0), so radiance functions can
/// read the film position back from the ray.
rt::ray film_ray(rt::real x, rt::real y)
{
    return rt::ray{rt::vec3(x, y, 0), rt::vec3(0, 0, -1)};
}

/// A radiance that depends on the position and on the sample's own random
/// numbers, so any change of sample order or seeding would show.
rt::color noisy_pattern(const rt::ray& r, rt::sample_context& ctx)
{
    const float x = float(r.origin.x), y = float(r.origin.y);
    const float noise = ctx.rng.next_float();
    return rt::color(std::sin(0.7f * x) * std::cos(0.45f * y) + noise, x * 0.01f + noise * noise, y * y * 0.001f);
}

/// The area of the unit pixel square [x, x+1] x [y, y+1] where a x' + b y' < c
/// (the polygon clipped by the half-plane, then the shoelace formula).
double covered_area(double x, double y, double a, double b, double c)
{
    const double corners[4][2] = {{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}};
    std::vector<std::array<double, 2>> clipped;
    for (int k = 0; k < 4; ++k) {
        const double* p = corners[k];
        const double* q = corners[(k + 1) % 4];
        const double fp = a * p[0] + b * p[1] - c, fq = a * q[0] + b * q[1] - c;
        if (fp < 0)
            clipped.push_back({p[0], p[1]});
        if ((fp < 0) != (fq < 0)) {
            const double t = fp / (fp - fq);
            clipped.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
        }
    }
    double twice_area = 0;
    for (std::size_t k = 0; k < clipped.size(); ++k) {
        const auto& p = clipped[k];
        const auto& q = clipped[(k + 1) % clipped.size()];
        twice_area += p[0] * q[1] - q[0] * p[1];
    }
    return std::fabs(twice_area) / 2;
}

/// The RMS difference between rendered and exact coverage over the partly
/// covered pixels of several slanted edges and seeds, at `spp` samples.
double edge_rms_error(rt::sampler_kind sampler, int spp, int* pixels = nullptr)
{
    const int width = 24, height = 64;
    // edges through the image at several angles from the vertical, each with its own seeds
    const double angles_degrees[] = {4, 11, 19.5, 26, 33, 41};
    double sum_squared = 0;
    int count = 0;
    for (int e = 0; e < 6; ++e) {
        const double angle = angles_degrees[e] * 3.14159265358979323846 / 180;
        const double a = std::cos(angle), b = -std::sin(angle);          // the edge's normal
        const double c = a * (width / 2.0 + 0.37 * e) + b * (height / 2.0); // through a point near the middle
        rt::render_options options;
        options.width = width;
        options.height = height;
        options.samples_per_pixel = spp;
        options.sampler = sampler;
        options.threads = 1;
        options.seed = std::uint64_t(1000 + 17 * e);
        const rt::image img = rt::render(options, film_ray, [&](const rt::ray& r, rt::sample_context&) {
                                  return rt::color(a * double(r.origin.x) + b * double(r.origin.y) < c ? 1.0f : 0.0f);
                              }).pixels;
        for (int row = 0; row < height; ++row)
            for (int column = 0; column < width; ++column) {
                // film coordinates of the pixel's bottom-left corner
                const double exact = covered_area(column, height - 1 - row, a, b, c);
                if (exact <= 1e-9 || exact >= 1 - 1e-9)
                    continue;
                const double error = double(img.at(column, row).r) - exact;
                sum_squared += error * error;
                ++count;
            }
    }
    REQUIRE(count > 300);
    if (pixels)
        *pixels = count;
    return std::sqrt(sum_squared / count);
}

/// The least-squares slope of log(error) against log(spp).
double log_log_slope(const std::vector<int>& spp, const std::vector<double>& error)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = double(spp.size());
    for (std::size_t k = 0; k < spp.size(); ++k) {
        const double x = std::log(double(spp[k])), y = std::log(error[k]);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

} // namespace

// ===========================================================================
// tone maps, exposure, transfer functions, quantisation

TEST_CASE("clamp tone map: identity on [0, 1], 0 below, 1 above, NaN to 0")
{
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
    CHECK(rt::tonemap_reinhard(0.0f) == 0.0f);
    CHECK(rt::tonemap_reinhard(1.0f) == doctest::Approx(0.5));  // 1 / 2
    CHECK(rt::tonemap_reinhard(3.0f) == doctest::Approx(0.75)); // 3 / 4
    CHECK(rt::tonemap_reinhard(0.25f) == doctest::Approx(0.2)); // (1/4) / (5/4)
    CHECK(rt::tonemap_reinhard(99.0f) == doctest::Approx(0.99));
    CHECK(rt::tonemap_reinhard(std::numeric_limits<float>::infinity()) == 1.0f); // the limit, not inf/inf
    CHECK(rt::tonemap_reinhard(-1.0f) == 0.0f);
    CHECK(rt::tonemap_reinhard(std::nanf("")) == 0.0f);
    // increasing and below 1 everywhere
    float previous = 0;
    for (float x = 0.01f; x < 1000; x *= 1.1f) {
        const float t = rt::tonemap_reinhard(x);
        CHECK(t > previous);
        CHECK(t < 1.0f);
        previous = t;
    }
}

TEST_CASE("the naive x / (1 + x) turns an infinite sample into a black pixel, the tone map does not")
{
    // a single overflowing sample (inf radiance) must come out white, not black
    const float inf = std::numeric_limits<float>::infinity();
    const float naive = inf / (1.0f + inf);
    CHECK(std::isnan(naive));                    // inf / inf
    CHECK(int(rt::quantize(rt::srgb_encode(naive))) == 0);           // NaN is stored as 0: black
    CHECK(int(rt::quantize(rt::srgb_encode(rt::tonemap_reinhard(inf)))) == 255); // the limit 1: white
}

TEST_CASE("ACES filmic fit: T(1) = 2.54 / 3.16, reaches 1 at x = 7.24 and stays there")
{
    // T(x) = x(2.51 x + 0.03) / (x(2.43 x + 0.59) + 0.14)
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
        CHECK(t > previous);
        previous = t;
    }
}

TEST_CASE("exposure: +1 stop doubles, -1 stop halves, 0 changes nothing")
{
    const rt::color c(0.1f, 0.5f, 3.0f);
    CHECK(rt::apply_exposure(c, 1.0f) == c * 2.0f);
    CHECK(rt::apply_exposure(c, -1.0f) == c * 0.5f);
    CHECK(rt::apply_exposure(c, 0.0f) == c);
    CHECK(rt::apply_exposure(c, 3.0f).b == doctest::Approx(24.0));
}

TEST_CASE("AOVs in 8 bits: data without a curve, and depth scaled by the image's farthest hit")
{
    // depths 0 (a miss), 1, 3 and 4: the farthest, 4, becomes 255 and the rest
    // scale with it, round(255 d / 4) = 0, 64, 191, 255
    rt::image depth(4, 1);
    const float d[] = {0.0f, 1.0f, 3.0f, 4.0f};
    for (int x = 0; x < 4; ++x)
        depth.at(x, 0) = rt::color(d[x]);
    const rt::encoding shaded{3.0f, rt::tonemap_kind::aces, rt::transfer_kind::srgb, 2.2f};
    const rt::encoding enc = rt::output_encoding(rt::aov_kind::depth, shaded, depth);
    const int expected[] = {0, 64, 191, 255};
    for (int x = 0; x < 4; ++x) {
        CAPTURE(x);
        CHECK(int(rt::encode_color(depth.at(x, 0), enc)[0]) == expected[x]);
    }
    // a farthest distance that is no power of two still reaches 255 exactly
    depth.at(3, 0) = rt::color(3.0f);
    CHECK(int(rt::encode_color(depth.at(3, 0), rt::output_encoding(rt::aov_kind::depth, shaded, depth))[0]) == 255);
    // normals are (n + 1) / 2 in [0, 1]: stored linearly, whatever the shaded settings
    const rt::encoding normals = rt::output_encoding(rt::aov_kind::normal, shaded, depth);
    CHECK(int(rt::encode_color(rt::color(0.5f), normals)[0]) == 128);
    // and the shaded image keeps its own settings
    CHECK(rt::output_encoding(rt::aov_kind::none, shaded, depth).tonemap == rt::tonemap_kind::aces);
}

TEST_CASE("sRGB encode at known points (IEC 61966-2-1)")
{
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
        CHECK(v > previous);
        CHECK(rt::srgb_decode(v) == doctest::Approx(x).epsilon(1e-5).scale(1e-3));
        previous = v;
    }
    // the decode side's own known point: v = 0.04045 is x = 0.04045 / 12.92
    CHECK(rt::srgb_decode(0.04045f) == doctest::Approx(0.04045 / 12.92).epsilon(1e-6));
}

TEST_CASE("a plain gamma 2.2 is not sRGB: up to 9 byte levels apart in the shadows")
{
    // by hand: x = 0.001 gives sRGB 12.92 x = 0.01292 -> byte 3, but
    // 0.001^(1/2.2) = 0.0433 -> byte 11; at mid-grey 0.18 the two are 118 and 117
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
    CHECK(worst == 9);           // near x = 0.0013, where sRGB is still on its linear segment
    CHECK(worst_x < 0.003f);
    CHECK(worst_above_tenth <= 2);
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

TEST_CASE("quantise: every level k/255 comes back as k, halves round up, the rest clamps")
{
    for (int k = 0; k <= 255; ++k) {
        CAPTURE(k);
        CHECK(int(rt::quantize(float(k) / 255)) == k);
        if (k < 255) {
            CHECK(int(rt::quantize((float(k) + 0.49f) / 255)) == k);
            CHECK(int(rt::quantize((float(k) + 0.51f) / 255)) == k + 1);
        }
    }
    CHECK(int(rt::quantize(0.5f)) == 128); // 127.5 rounds up
    CHECK(int(rt::quantize(-0.1f)) == 0);
    CHECK(int(rt::quantize(1.7f)) == 255);
    CHECK(int(rt::quantize(std::numeric_limits<float>::infinity())) == 255);
    CHECK(int(rt::quantize(std::nanf(""))) == 0);
}

TEST_CASE("the pipeline runs exposure, tone map, transfer, quantisation in that order")
{
    rt::encoding enc;
    enc.exposure = 1;
    enc.tonemap = rt::tonemap_kind::reinhard;
    enc.transfer = rt::transfer_kind::srgb;
    // 0.5 * 2^1 = 1 -> Reinhard 1/2 -> sRGB 0.7353570 -> 255 * 0.7353570 = 187.52 -> 188
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

    // and through a file written by save_image
    scratch_folder folder("pfm");
    rt::save_image(folder.path / "round.pfm", img, rt::encoding{});
    std::ifstream in(folder.path / "round.pfm", std::ios::binary);
    CHECK(identical(rt::read_pfm(in, "round.pfm"), img));
}

TEST_CASE("atomic output: a write that fails half-way leaves the earlier file intact and nothing else")
{
    scratch_folder folder("atomic");
    const std::filesystem::path target = folder.path / "render.ppm";
    rt::image first(2, 1, rt::color(0.5f));
    rt::save_image(target, first, rt::encoding{});
    const std::string before = read_all(target);
    REQUIRE(before.size() == std::string("P6\n2 1\n255\n").size() + 6);

    // a writer that has written part of a new image when it fails
    rt::image second(64, 64, rt::color(0.9f));
    CHECK_THROWS_AS(rt::write_atomically(target,
                                         [&](std::ostream& out) {
                                             rt::write_ppm(out, second, rt::encoding{});
                                             out.flush();
                                             throw std::runtime_error("induced failure half-way");
                                         }),
                    std::runtime_error);
    CHECK(read_all(target) == before);
    // no temporary file is left beside it
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder.path)) {
        CAPTURE(entry.path().string());
        ++files;
    }
    CHECK(files == 1);

    // an unwritable destination is an error before anything is written
    CHECK_THROWS_AS(rt::save_image(folder.path / "missing-folder" / "x.png", first, rt::encoding{}), rt::error);
    CHECK_THROWS_AS(rt::save_image(folder.path, first, rt::encoding{}), rt::error); // a folder, not a file
    CHECK_THROWS_AS(rt::save_image(folder.path / "x.jpg", first, rt::encoding{}), rt::error);
    CHECK_THROWS_AS(rt::check_image_output(folder.path / "x.jpg"), rt::error); // checked before rendering
    CHECK_THROWS_AS(rt::check_image_output(folder.path / "missing-folder" / "x.png"), rt::error);
    CHECK_NOTHROW(rt::check_image_output(folder.path / "next.PNG"));
    CHECK(read_all(target) == before);
}

// ===========================================================================
// random numbers and samplers

TEST_CASE("pcg32 reproduces O'Neill's reference output (pcg32-demo, seed 42, stream 54)")
{
    // the first outputs printed by pcg32-demo of the reference pcg-c-basic
    // package (pcg-random.org) for pcg32_srandom_r(&rng, 42u, 54u)
    rt::pcg32 rng(42u, 54u);
    CHECK(rng.next_u32() == 0xa15c02b7u);
    CHECK(rng.next_u32() == 0x7b47f409u);
    CHECK(rng.next_u32() == 0xba1d3330u);
    CHECK(rng.next_u32() == 0x83d2f293u);
    CHECK(rng.next_u32() == 0xbfa4784bu);
    CHECK(rng.next_u32() == 0xcbed606eu);
}

TEST_CASE("pcg32 floats are uniform in 0 <= u < 1 and next_below has no modulo bias")
{
    rt::pcg32 rng(2024, 1);
    const int n = 200000;
    double sum = 0, sum_squared = 0;
    for (int k = 0; k < n; ++k) {
        const float u = rng.next_float();
        REQUIRE(u >= 0.0f);
        REQUIRE(u < 1.0f);
        sum += u;
        sum_squared += double(u) * u;
    }
    // mean 1/2 with standard error sqrt(1/12 / n) = 6.5e-4: 5 sigma = 3.2e-3
    CHECK(std::fabs(sum / n - 0.5) < 3.2e-3);
    CHECK(sum_squared / n - (sum / n) * (sum / n) == doctest::Approx(1.0 / 12).epsilon(0.02));

    int counts[3] = {0, 0, 0};
    for (int k = 0; k < 30000; ++k)
        ++counts[rng.next_below(3)];
    // each 10000 expected, sd sqrt(30000 * 1/3 * 2/3) = 82: 5 sigma = 410
    for (int c : counts)
        CHECK(std::abs(c - 10000) < 410);
}

TEST_CASE("grid shape for spp samples: a square for squares, else ceil(sqrt) columns")
{
    CHECK(rt::grid_shape_for(1).columns == 1);
    CHECK(rt::grid_shape_for(16).columns == 4);
    CHECK(rt::grid_shape_for(16).rows == 4);
    const int spp[] = {2, 5, 8, 12};
    const int columns[] = {2, 3, 3, 4};
    const int rows[] = {1, 2, 3, 3};
    for (int k = 0; k < 4; ++k) {
        CHECK(rt::grid_shape_for(spp[k]).columns == columns[k]);
        CHECK(rt::grid_shape_for(spp[k]).rows == rows[k]);
    }
    for (int n = 1; n <= 400; ++n) {
        const rt::grid_shape g = rt::grid_shape_for(n);
        CAPTURE(n);
        CHECK(g.columns * g.columns >= n);
        CHECK((g.columns - 1) * (g.columns - 1) < n);
        CHECK(g.columns * g.rows >= n);
        CHECK(g.columns * g.rows < n + g.columns);
        CHECK(rt::effective_samples(rt::sampler_kind::jittered, n) == g.columns * g.rows);
        CHECK(rt::effective_samples(rt::sampler_kind::random, n) == n);
        CHECK(rt::effective_samples(rt::sampler_kind::halton, n) == n);
        CHECK(rt::effective_samples(rt::sampler_kind::center, n) == 1);
    }
}

TEST_CASE("center and grid samplers place samples at cell centres")
{
    std::vector<rt::vec2> s;
    rt::pixel_samples(rt::sampler_kind::center, 64, 1, 5, s);
    REQUIRE(s.size() == 1);
    CHECK(s[0].x == rt::real(0.5));
    CHECK(s[0].y == rt::real(0.5));

    rt::pixel_samples(rt::sampler_kind::grid, 6, 1, 5, s); // 3 columns x 2 rows
    REQUIRE(s.size() == 6);
    for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 3; ++a) {
            const rt::vec2 p = s[std::size_t(b * 3 + a)];
            CHECK(p.x == doctest::Approx((a + 0.5) / 3));
            CHECK(p.y == doctest::Approx((b + 0.5) / 2));
        }
}

TEST_CASE("jittered: one sample in every cell, and every sampler stays inside the unit pixel square")
{
    std::vector<rt::vec2> s;
    for (std::uint64_t pixel = 0; pixel < 200; ++pixel) {
        rt::pixel_samples(rt::sampler_kind::jittered, 16, 9, pixel, s);
        REQUIRE(s.size() == 16);
        int cells[16] = {};
        for (const rt::vec2& p : s)
            ++cells[int(p.y * 4) * 4 + int(p.x * 4)];
        for (int c : cells)
            CHECK(c == 1);
    }
    for (auto kind : {rt::sampler_kind::center, rt::sampler_kind::grid, rt::sampler_kind::random,
                      rt::sampler_kind::jittered, rt::sampler_kind::halton})
        for (int spp : {1, 2, 7, 64, 1000})
            for (std::uint64_t pixel = 0; pixel < 50; ++pixel) {
                rt::pixel_samples(kind, spp, 3, pixel, s);
                CHECK(int(s.size()) == rt::effective_samples(kind, spp));
                for (const rt::vec2& p : s) {
                    CHECK(p.x >= 0);
                    CHECK(p.x < 1);
                    CHECK(p.y >= 0);
                    CHECK(p.y < 1);
                }
            }
}

TEST_CASE("samples are a function of (seed, pixel): the same twice, different elsewhere")
{
    for (auto kind : {rt::sampler_kind::random, rt::sampler_kind::jittered, rt::sampler_kind::halton}) {
        std::vector<rt::vec2> a, b, other_pixel, other_seed;
        rt::pixel_samples(kind, 8, 77, 1234, a);
        rt::pixel_samples(kind, 8, 77, 1234, b);
        rt::pixel_samples(kind, 8, 77, 1235, other_pixel);
        rt::pixel_samples(kind, 8, 78, 1234, other_seed);
        CHECK(a == b);
        CHECK(a != other_pixel);
        CHECK(a != other_seed);
    }
}

TEST_CASE("radical inverse: the Halton points by hand")
{
    // base 2: 1 = 1b -> 0.1b, 2 = 10b -> 0.01b, 3 = 11b -> 0.11b, 6 = 110b -> 0.011b
    CHECK(rt::radical_inverse(2, 0) == 0.0);
    CHECK(rt::radical_inverse(2, 1) == 0.5);
    CHECK(rt::radical_inverse(2, 2) == 0.25);
    CHECK(rt::radical_inverse(2, 3) == 0.75);
    CHECK(rt::radical_inverse(2, 6) == 0.375);
    // base 3: 1 -> 1/3, 2 -> 2/3, 3 = 10 -> 1/9, 5 = 12 -> 2/3 + 1/9 = 7/9
    CHECK(rt::radical_inverse(3, 1) == doctest::Approx(1.0 / 3));
    CHECK(rt::radical_inverse(3, 2) == doctest::Approx(2.0 / 3));
    CHECK(rt::radical_inverse(3, 3) == doctest::Approx(1.0 / 9));
    CHECK(rt::radical_inverse(3, 5) == doctest::Approx(7.0 / 9));
}

TEST_CASE("scrambled Halton keeps its stratification in every pixel")
{
    std::vector<rt::vec2> s;
    for (std::uint64_t pixel = 0; pixel < 100; ++pixel) {
        rt::pixel_samples(rt::sampler_kind::halton, 27, 5, pixel, s);
        REQUIRE(s.size() == 27);
        // the first 16 points: one x in each [m/16, (m+1)/16)
        int x_bins[16] = {};
        for (int k = 0; k < 16; ++k)
            ++x_bins[int(s[std::size_t(k)].x * 16)];
        for (int c : x_bins)
            CHECK(c == 1);
        // all 27 points: one y in each [m/27, (m+1)/27)
        int y_bins[27] = {};
        for (int k = 0; k < 27; ++k)
            ++y_bins[int(s[std::size_t(k)].y * 27)];
        for (int c : y_bins)
            CHECK(c == 1);
    }
}

// ===========================================================================
// reconstruction filters

TEST_CASE("filters at known points")
{
    const rt::filter box = rt::make_filter(rt::filter_kind::box);
    const rt::filter tent = rt::make_filter(rt::filter_kind::tent);
    const rt::filter gauss = rt::make_filter(rt::filter_kind::gaussian);
    const rt::filter mitchell = rt::make_filter(rt::filter_kind::mitchell);
    CHECK(box.radius == rt::real(0.5));
    CHECK(tent.radius == rt::real(1));
    CHECK(gauss.radius == rt::real(1.5));
    CHECK(mitchell.radius == rt::real(2));

    CHECK(rt::filter_value(box, 0.49) == 1);
    CHECK(rt::filter_value(box, -0.5) == 0); // the support is open: |x| < r
    CHECK(rt::filter_value(tent, 0.0) == 1);
    CHECK(rt::filter_value(tent, 0.25) == doctest::Approx(0.75));
    CHECK(rt::filter_value(tent, -0.5) == doctest::Approx(0.5));
    CHECK(rt::filter_value(tent, 1.0) == 0);
    // Gaussian, s = 1/2: exp(-x^2 / (2 s^2)) - exp(-r^2 / (2 s^2)) = exp(-2 x^2) - exp(-4.5)
    CHECK(rt::filter_value(gauss, 0.0) == doctest::Approx(1 - std::exp(-4.5)));
    CHECK(rt::filter_value(gauss, 1.0) == doctest::Approx(std::exp(-2.0) - std::exp(-4.5)));
    CHECK(rt::filter_value(gauss, 1.5) == 0);
    // Mitchell-Netravali, B = C = 1/3, radius 2 (k at x itself):
    // k(0) = (6 - 2B)/6 = 8/9; k(1) = B/6 = 1/18; k(1.5) = -5/144; k(2) = 0
    CHECK(rt::filter_value(mitchell, 0.0) == doctest::Approx(8.0 / 9));
    CHECK(rt::filter_value(mitchell, 1.0) == doctest::Approx(1.0 / 18));
    CHECK(rt::filter_value(mitchell, -1.5) == doctest::Approx(-5.0 / 144));
    CHECK(rt::filter_value(mitchell, 2.0) == 0);
    // the 2D weight is the product
    CHECK(rt::filter_weight(tent, 0.5, 0.25) == doctest::Approx(0.5 * 0.75));
}

TEST_CASE("filters integrate to their closed-form integral, so normalised weights integrate to 1")
{
    for (auto kind : {rt::filter_kind::box, rt::filter_kind::tent, rt::filter_kind::gaussian, rt::filter_kind::mitchell})
        for (double radius : {0.5, 1.0, 1.5, 2.0, 3.0}) {
            const rt::filter f = rt::make_filter(kind, rt::real(radius));
            CAPTURE(rt::name_of(kind));
            CAPTURE(radius);
            // midpoint rule over [-r, r]
            const int n = 200000;
            const double h = 2 * radius / n;
            double integral = 0;
            for (int k = 0; k < n; ++k)
                integral += rt::filter_value(f, -radius + (k + 0.5) * h) * h;
            CHECK(integral == doctest::Approx(rt::filter_integral(f)).epsilon(1e-6));
            CHECK(integral / rt::filter_integral(f) == doctest::Approx(1).epsilon(1e-6));
        }
    // Mitchell-Netravali's k integrates to 1 (radius 2): sum over both halves of
    // (3 - B/4 + C/2) + (B/4 - C/2) = 3, times 2 / 6
    CHECK(rt::filter_integral(rt::make_filter(rt::filter_kind::mitchell)) == doctest::Approx(1));
}

TEST_CASE("box, tent and Mitchell-Netravali at their default radii are partitions of unity")
{
    // sum over the integer shifts n of f(x - n) = 1 for every x: a flat field
    // sampled at the pixel centres is reconstructed flat
    for (auto kind : {rt::filter_kind::box, rt::filter_kind::tent, rt::filter_kind::mitchell}) {
        const rt::filter f = rt::make_filter(kind);
        for (double x = 0.003; x < 1; x += 0.01) {
            double sum = 0;
            for (int n = -4; n <= 4; ++n)
                sum += rt::filter_value(f, x - n);
            CHECK(sum == doctest::Approx(1).epsilon(1e-12));
        }
    }
}

TEST_CASE("filter reach: the pixels beyond its own that a pixel's filter touches")
{
    CHECK(rt::filter_reach(rt::make_filter(rt::filter_kind::box)) == 0);
    CHECK(rt::filter_reach(rt::make_filter(rt::filter_kind::tent)) == 1);
    CHECK(rt::filter_reach(rt::make_filter(rt::filter_kind::gaussian)) == 1);
    CHECK(rt::filter_reach(rt::make_filter(rt::filter_kind::mitchell)) == 2);
    CHECK(rt::filter_reach(rt::make_filter(rt::filter_kind::box, rt::real(0.51))) == 1);
}

// ===========================================================================
// the renderer

TEST_CASE("the renderer passes film positions from the bottom-left and stores the top row first")
{
    rt::render_options options;
    options.width = 4;
    options.height = 3;
    options.sampler = rt::sampler_kind::center;
    const rt::image img = rt::render(options, film_ray, [](const rt::ray& r, rt::sample_context& ctx) {
                              CHECK(ctx.film.x == r.origin.x);
                              CHECK(ctx.film.y == r.origin.y);
                              return rt::color(float(r.origin.x), float(r.origin.y), float(ctx.y));
                          }).pixels;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 4; ++column) {
            CHECK(img.at(column, row).r == float(column) + 0.5f);
            CHECK(img.at(column, row).g == float(2 - row) + 0.5f); // image row 0 is film row 2
            CHECK(img.at(column, row).b == float(row));
        }
}

TEST_CASE("a constant image stays constant with every sampler and filter, borders included")
{
    const rt::color value(0.3f, 0.6f, 0.9f);
    for (auto sampler : {rt::sampler_kind::center, rt::sampler_kind::grid, rt::sampler_kind::random,
                         rt::sampler_kind::jittered, rt::sampler_kind::halton})
        for (auto kind : {rt::filter_kind::box, rt::filter_kind::tent, rt::filter_kind::gaussian, rt::filter_kind::mitchell}) {
            rt::render_options options;
            options.width = 9;
            options.height = 7;
            options.samples_per_pixel = 5;
            options.sampler = sampler;
            options.reconstruction = rt::make_filter(kind);
            options.threads = 2;
            const rt::image img =
                rt::render(options, film_ray, [&](const rt::ray&, rt::sample_context&) { return value; }).pixels;
            for (const rt::color& c : img.pixels)
                for (int channel = 0; channel < 3; ++channel)
                    CHECK(c[channel] == doctest::Approx(value[channel]).epsilon(1e-6));
        }
}

TEST_CASE("the image is bit-identical for 1, 2 and 4 threads, any tile size, every run")
{
    for (auto kind : {rt::filter_kind::box, rt::filter_kind::mitchell}) {
        rt::render_options options;
        options.width = 45;
        options.height = 31;
        options.samples_per_pixel = 4;
        options.sampler = rt::sampler_kind::jittered;
        options.reconstruction = rt::make_filter(kind);
        options.seed = 2718;
        options.tile_size = 8;
        options.threads = 1;
        const rt::image reference = rt::render(options, film_ray, noisy_pattern).pixels;
        for (int threads : {1, 2, 4}) {
            for (int tile : {5, 8, 32}) {
                options.threads = threads;
                options.tile_size = tile;
                CAPTURE(threads);
                CAPTURE(tile);
                CHECK(identical(rt::render(options, film_ray, noisy_pattern).pixels, reference));
            }
        }
        // and the seed matters
        options.seed = 2719;
        CHECK_FALSE(identical(rt::render(options, film_ray, noisy_pattern).pixels, reference));
    }
}

TEST_CASE("crops rendered apart and pasted together equal the full render bit for bit")
{
    for (auto kind : {rt::filter_kind::box, rt::filter_kind::tent, rt::filter_kind::mitchell}) {
        rt::render_options options;
        options.width = 37;
        options.height = 23;
        options.samples_per_pixel = 3;
        options.sampler = rt::sampler_kind::halton;
        options.reconstruction = rt::make_filter(kind);
        options.seed = 99;
        options.threads = 2;
        options.tile_size = 16;
        const rt::image full = rt::render(options, film_ray, noisy_pattern).pixels;

        // uneven pieces: columns [0, 13) [13, 37), rows [0, 9) [9, 22) [22, 23)
        rt::image merged(37, 23, rt::color(-1.0f));
        const int xs[] = {0, 13, 37}, ys[] = {0, 9, 22, 23};
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 3; ++j) {
                options.crop = rt::crop_window{xs[i], xs[i + 1], ys[j], ys[j + 1]};
                options.threads = 1 + (i + j) % 3;
                const rt::image piece = rt::render(options, film_ray, noisy_pattern).pixels;
                REQUIRE(piece.width == xs[i + 1] - xs[i]);
                REQUIRE(piece.height == ys[j + 1] - ys[j]);
                rt::paste(merged, piece, xs[i], ys[j]);
            }
        CAPTURE(rt::name_of(kind));
        CHECK(identical(merged, full));

        // a single pixel too
        options.crop = rt::crop_window{20, 21, 11, 12};
        const rt::image one = rt::render(options, film_ray, noisy_pattern).pixels;
        CHECK(bits_of(one.at(0, 0).r) == bits_of(full.at(20, 11).r));
        CHECK(bits_of(one.at(0, 0).g) == bits_of(full.at(20, 11).g));
    }
}

TEST_CASE("a half-covered pixel converges to its coverage, jittered faster than random")
{
    // The RMS error over the partly covered pixels of slanted edges. Random
    // sampling: a binomial estimate, error sqrt(c (1 - c) / N), slope -1/2 in
    // log-log. Jittered (one sample per cell of a sqrt(N) x sqrt(N) grid):
    // only the ~sqrt(N) cells the edge crosses are uncertain, error ~ N^(-3/4)
    // (D. P. Mitchell, "Consequences of Stratified Sampling in Graphics",
    // SIGGRAPH 1996). Fixed seeds make the figures the same on every run.
    const std::vector<int> spp = {4, 16, 64, 256};
    std::vector<double> random_error, jittered_error, halton_error;
    int pixels = 0;
    for (int n : spp) {
        random_error.push_back(edge_rms_error(rt::sampler_kind::random, n, &pixels));
        jittered_error.push_back(edge_rms_error(rt::sampler_kind::jittered, n));
        halton_error.push_back(edge_rms_error(rt::sampler_kind::halton, n));
    }
    const double random_slope = log_log_slope(spp, random_error);
    const double jittered_slope = log_log_slope(spp, jittered_error);
    const double halton_slope = log_log_slope(spp, halton_error);
    std::ostringstream table;
    table << "edge RMS error over " << pixels << " pixels (spp: random jittered halton):";
    for (std::size_t k = 0; k < spp.size(); ++k)
        table << "  " << spp[k] << ": " << random_error[k] << " " << jittered_error[k] << " " << halton_error[k];
    table << "  slopes " << random_slope << " " << jittered_slope << " " << halton_slope;
    MESSAGE(table.str());

    for (std::size_t k = 0; k < spp.size(); ++k) {
        CAPTURE(spp[k]);
        CHECK(jittered_error[k] < random_error[k]);
        CHECK(halton_error[k] < random_error[k]);
    }
    CHECK(random_slope == doctest::Approx(-0.5).epsilon(0.2));   // within 0.1 of -1/2
    CHECK(jittered_slope == doctest::Approx(-0.75).epsilon(0.2)); // within 0.15 of -3/4
    CHECK(jittered_slope < random_slope - 0.15);
    // at 256 spp jittered is several times more accurate than random
    CHECK(jittered_error.back() * 2.5 < random_error.back());
}

TEST_CASE("progress: reported from the calling thread, complete at the end, rays counted")
{
    rt::render_options options;
    options.width = 40;
    options.height = 30;
    options.samples_per_pixel = 4;
    options.threads = 2;
    options.tile_size = 8;
    std::vector<rt::render_progress> reports;
    const std::thread::id caller = std::this_thread::get_id();
    const rt::render_result out = rt::render(
        options, film_ray,
        [](const rt::ray&, rt::sample_context& ctx) {
            ctx.rays += 2; // as if the radiance function traced two more rays
            return rt::color(0.5f);
        },
        [&](const rt::render_progress& p) {
            CHECK(std::this_thread::get_id() == caller);
            reports.push_back(p);
        });
    REQUIRE_FALSE(reports.empty());
    CHECK(reports.back().pixels_done == 1200);
    CHECK(reports.back().pixels_total == 1200);
    for (std::size_t k = 1; k < reports.size(); ++k)
        CHECK(reports[k].pixels_done >= reports[k - 1].pixels_done);
    CHECK(out.stats.camera_rays == 1200u * 4u); // box filter: no border samples
    CHECK(out.stats.extra_rays == 2u * 1200u * 4u);
    CHECK(reports.back().rays == 3u * 1200u * 4u);
    CHECK(out.stats.samples_per_pixel == 4);
    CHECK(out.stats.threads == 2);
    CHECK(out.stats.tiles == 5u * 4u);
}

TEST_CASE("an exception in the radiance function stops the render and is rethrown")
{
    rt::render_options options;
    options.width = 64;
    options.height = 64;
    options.threads = 4;
    options.tile_size = 4;
    std::atomic<int> calls{0};
    CHECK_THROWS_AS(rt::render(options, film_ray,
                               [&](const rt::ray& r, rt::sample_context&) -> rt::color {
                                   ++calls;
                                   if (r.origin.x > 30 && r.origin.y > 30)
                                       throw rt::exercise_not_done("stage 05: shade");
                                   return rt::color(1.0f);
                               }),
                    rt::exercise_not_done);
    CHECK(calls.load() < 64 * 64); // the workers stopped early
}

TEST_CASE("render options are checked, one line each")
{
    auto ok = [] { return rt::render_options{}; };
    auto message = [](const rt::render_options& o) {
        try {
            rt::check_render_options(o);
        } catch (const rt::error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    rt::render_options o = ok();
    CHECK(message(o).empty());
    o.width = 0;
    CHECK(message(o).find("expected an image of at least 1x1 pixels, found 0x480") != std::string::npos);
    o = ok();
    o.samples_per_pixel = 0;
    CHECK(message(o).find("expected at least 1 sample per pixel, found 0") != std::string::npos);
    o = ok();
    o.crop = rt::crop_window{10, 10, 0, 5};
    CHECK(message(o).find("expected a crop 0 <= x0 < x1 <= 640") != std::string::npos);
    o.crop = rt::crop_window{0, 641, 0, 5};
    CHECK_FALSE(message(o).empty());
    o.crop = rt::crop_window{0, 640, 0, 480};
    CHECK(message(o).empty());
    o = ok();
    o.width = o.height = 65536; // 2^32 pixels: too many for memory, unless cropped
    CHECK(message(o).find("expected at most 268435456 pixels to render") != std::string::npos);
    o.crop = rt::crop_window{0, 1024, 60000, 61024};
    CHECK(message(o).empty());
    o = ok();
    o.reconstruction.radius = 0;
    CHECK(message(o).find("expected a filter radius in (0, 16] pixels") != std::string::npos);
    CHECK(message(o).find('\n') == std::string::npos);
    CHECK_THROWS_AS(rt::render(o, film_ray, [](const rt::ray&, rt::sample_context&) { return rt::color(0.0f); }),
                    rt::error);
}

TEST_CASE("progress line and summary: percent, ETA = elapsed (total - done) / done, rays per second")
{
    rt::render_progress p;
    p.pixels_done = 25;
    p.pixels_total = 100;
    p.seconds = 3;
    p.rays = 4500000;
    const std::string line = rt::progress_line(p, 20);
    CHECK(line.substr(0, 22) == "[#####...............]");
    CHECK(line.find(" 25%") != std::string::npos);
    CHECK(line.find("elapsed 3.00 s") != std::string::npos);
    CHECK(line.find("ETA 9.00 s") != std::string::npos);      // 3 * 75 / 25
    CHECK(line.find("1.50 Mrays/s") != std::string::npos);    // 4.5e6 / 3
    p.pixels_done = 0;
    CHECK(rt::progress_line(p).find("ETA ?") != std::string::npos);

    CHECK(rt::format_duration(0.5) == "0.50 s");
    CHECK(rt::format_duration(42.26) == "42.3 s");
    CHECK(rt::format_duration(125) == "2 min 05 s");
    CHECK(rt::format_duration(3 * 3600 + 7 * 60) == "3 h 07 min");
    CHECK(rt::format_count(950) == "950");
    CHECK(rt::format_count(12345) == "12.3 k");
    CHECK(rt::format_count(4.56e6) == "4.56 M");

    rt::render_stats s;
    s.width = 640;
    s.height = 360;
    s.samples_per_pixel = 16;
    s.threads = 2;
    s.camera_rays = 3000000;
    s.extra_rays = 1000000;
    s.seconds = 2;
    CHECK(rt::summary_line(s) == "rendered 640x360 at 16 spp on 2 threads: 4.00 Mrays in 2.00 s (2.00 Mrays/s)");

    // a disabled bar writes nothing
    std::ostringstream sink;
    rt::progress_bar quiet_bar(sink, false);
    quiet_bar.update(p);
    quiet_bar.finish();
    CHECK(sink.str().empty());
    rt::progress_bar bar(sink, true);
    bar.update(p);
    CHECK(sink.str().substr(0, 2) == "\r[");
}

TEST_CASE("camera statement numbers: the shortest text when it reads back exactly, else 17 digits")
{
    // The scene loader reads a number as a double and rounds it to rt::real;
    // the text must survive that path exactly, whatever rt::real is.
    auto read_back = [](const std::string& text) {
        double parsed = 0;
        const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), parsed);
        if (status != std::errc() || end != text.data() + text.size())
            return std::numeric_limits<rt::real>::quiet_NaN(); // equal to nothing
        return rt::real(parsed);
    };
    // the stream's default 6 digits lose the camera: 1/3 comes back as 0.333333
    std::ostringstream six_digits;
    six_digits << rt::real(1) / rt::real(3);
    CHECK(read_back(six_digits.str()) != rt::real(1) / rt::real(3));
    CHECK(rt::exact_number_text(rt::real(0)) == "0");
    CHECK(rt::exact_number_text(rt::real(40)) == "40");
    CHECK(rt::exact_number_text(rt::real(1.6)) == "1.6");     // the real nearest 1.6, written short
    CHECK(rt::exact_number_text(rt::real(-0.3)) == "-0.3");
    // every bit pattern of a finite real, sampled: 20000 of them, plus the extremes
    std::vector<rt::real> values = {std::numeric_limits<rt::real>::max(), std::numeric_limits<rt::real>::lowest(),
                                    std::numeric_limits<rt::real>::min(), std::numeric_limits<rt::real>::denorm_min(),
                                    rt::real(0.1), rt::real(1) / rt::real(3)};
    rt::pcg32 rng(7, 11);
    while (values.size() < 20006) {
        rt::real value = 0;
        if constexpr (sizeof(rt::real) == 4) {
            const std::uint32_t bits = rng.next_u32();
            std::memcpy(&value, &bits, sizeof value);
        } else {
            const std::uint64_t bits = (std::uint64_t(rng.next_u32()) << 32) | rng.next_u32();
            std::memcpy(&value, &bits, sizeof value);
        }
        if (std::isfinite(value))
            values.push_back(value);
    }
    int wrong = 0;
    for (const rt::real value : values)
        if (read_back(rt::exact_number_text(value)) != value)
            ++wrong;
    CHECK(wrong == 0);
}

TEST_CASE("camera statement: the scene file's camera arguments, every field stated")
{
    rt::camera cam;
    cam.eye = rt::vec3(0, rt::real(1.6), 6);
    cam.look_at = rt::vec3(0, rt::real(0.7), 0);
    cam.up = rt::vec3(0, 1, 0);
    cam.fov_degrees = rt::real(40);
    CHECK(rt::camera_statement(cam) == "perspective eye 0 1.6 6 look_at 0 0.7 0 up 0 1 0 fov 40 focal 1");
    cam.fov_degrees.reset(); // the default field of view is left to the loader
    CHECK(rt::camera_statement(cam) == "perspective eye 0 1.6 6 look_at 0 0.7 0 up 0 1 0 focal 1");
    cam.kind = rt::projection::orthographic;
    cam.plane = rt::window{-4, 4, -3, rt::real(2.5)};
    cam.focal_distance = 2;
    CHECK(rt::camera_statement(cam) == "orthographic eye 0 1.6 6 look_at 0 0.7 0 up 0 1 0 window -4 4 -3 2.5 focal 2");
}

namespace {

/// A box [0, 8] x [0, 3] x [0, 4] as OBJ text, its faces turned outwards (an
/// object) or inwards (a room), with face `missing` left out (-x, +x, -y, +y,
/// -z, +z are 0 ... 5; -1: none).
float real_bit(int bits, int axis) { return float((bits >> axis) & 1); }

std::string box_obj(bool inward, int missing)
{
    const rt::vec3 size(8, 3, 4);
    auto corner = [&](int bits) {
        return rt::vec3(real_bit(bits, 0) * size.x, real_bit(bits, 1) * size.y, real_bit(bits, 2) * size.z);
    };
    std::string text;
    for (int bits = 0; bits < 8; ++bits) {
        const rt::vec3 c = corner(bits);
        text += "v " + std::to_string(c.x) + " " + std::to_string(c.y) + " " + std::to_string(c.z) + "\n";
    }
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            if (2 * axis + side == missing)
                continue;
            const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
            int quad[4];
            const int cycle[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            for (int k = 0; k < 4; ++k)
                quad[k] = (side << axis) | (cycle[k][0] << a1) | (cycle[k][1] << a2);
            const rt::vec3 n = glm::cross(corner(quad[1]) - corner(quad[0]), corner(quad[2]) - corner(quad[0]));
            const bool outwards = (n[axis] > 0) == (side == 1);
            if (outwards == inward)
                std::swap(quad[1], quad[3]);
            text += "f " + std::to_string(quad[0] + 1) + " " + std::to_string(quad[1] + 1) + " " +
                    std::to_string(quad[2] + 1) + " " + std::to_string(quad[3] + 1) + "\n";
        }
    return text;
}

} // namespace

TEST_CASE("a bare OBJ is framed from outside, or seen from inside when it is a room")
{
    scratch_folder folder("framing");
    auto camera_of = [&](bool inward, int missing) {
        const std::filesystem::path path = folder.path / "box.obj";
        std::ofstream(path, std::ios::binary) << box_obj(inward, missing);
        return rt::load_input(path).cam;
    };
    const rt::vec3 centre(4, 1.5f, 2);
    const float radius = glm::length(rt::vec3(8, 3, 4)) / 2;
    SUBCASE("a closed room: the eye at the centre, looking along the longest horizontal axis (x)")
    {
        const rt::camera cam = camera_of(true, -1);
        CHECK(cam.eye == centre);
        const rt::vec3 view = cam.look_at - cam.eye;
        CHECK(std::fabs(view.x) == doctest::Approx(glm::length(view)));
    }
    SUBCASE("a room open to the sky (no ceiling) is a room too")
    {
        CHECK(camera_of(true, 3).eye == centre);
    }
    SUBCASE("the same box wound outwards is an object: seen from outside its bounding sphere")
    {
        const rt::camera cam = camera_of(false, -1);
        CHECK(glm::length(cam.eye - centre) > radius);
        CHECK(cam.look_at == centre);
    }
    SUBCASE("a room without a front wall (the Cornell box) is seen from outside")
    {
        CHECK(glm::length(camera_of(true, 5).eye - centre) > radius);
    }
}
