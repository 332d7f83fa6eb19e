// library_renderer.cpp - the renderer (include/rt/rendering/renderer.hpp) and what it
// uses: the pcg32 generator, samplers, reconstruction filters, tiles and
// threads (bit-identical images for any thread count), crops, progress, the
// render options' checks, camera statements and the framing of a bare OBJ.
// Tested with hand-made ray sources and analytic radiance functions (a
// constant, a half-plane, a function of the film position); no exercise is
// called.
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
#include <rt/core/decimal_text.hpp>
#include <rt/output/encoding.hpp>
#include <rt/core/error.hpp>
#include <rt/rendering/filter.hpp>
#include <rt/core/image.hpp>
#include <rt/output/image_io.hpp>
#include <rt/rendering/progress.hpp>
#include <rt/core/random.hpp>
#include <rt/core/ray.hpp>
#include <rt/rendering/render_setup.hpp>
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
    const std::string line = rt::detail::progress_line(p, 20);
    CHECK(line.substr(0, 22) == "[#####...............]");
    CHECK(line.find(" 25%") != std::string::npos);
    CHECK(line.find("elapsed 3.00 s") != std::string::npos);
    CHECK(line.find("ETA 9.00 s") != std::string::npos);      // 3 * 75 / 25
    CHECK(line.find("1.50 Mrays/s") != std::string::npos);    // 4.5e6 / 3
    p.pixels_done = 0;
    CHECK(rt::detail::progress_line(p).find("ETA ?") != std::string::npos);

    CHECK(rt::detail::format_duration(0.5) == "0.50 s");
    CHECK(rt::detail::format_duration(42.26) == "42.3 s");
    CHECK(rt::detail::format_duration(125) == "2 min 05 s");
    CHECK(rt::detail::format_duration(3 * 3600 + 7 * 60) == "3 h 07 min");
    CHECK(rt::detail::format_count(950) == "950");
    CHECK(rt::detail::format_count(12345) == "12.3 k");
    CHECK(rt::detail::format_count(4.56e6) == "4.56 M");

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
        if (rt::detail::read_decimal<rt::real>(text.data(), text.data() + text.size(), parsed) !=
            rt::detail::decimal_reading::number)
            return std::numeric_limits<rt::real>::quiet_NaN(); // equal to nothing
        return rt::real(rt::detail::rounded_to<rt::real>(parsed));
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
