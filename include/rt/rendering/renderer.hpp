// renderer.hpp - the image from a ray source and a radiance function: samples,
// reconstruction, tiles and threads (stage 08).
//
//     rt::render_result out = rt::render(options,
//         [&](rt::real x, rt::real y) { return rt::generate_ray(gen, x, y); },     // the ray source
//         [&](const rt::ray& r, rt::sample_context& ctx) { return trace(r, ctx); }); // radiance
//
// The renderer knows nothing of scenes: it asks the ray source for the ray
// through the film position (x, y) (pixels from the image's bottom-left corner,
// as rt::generate_ray takes them) and the radiance function for the color
// that ray brings back. Both are called from several threads at once, so they
// must not modify shared state (read-only scene data is fine).
//
// A pixel's value (filter.hpp):
//     I(p) = sum f(s - c) L(s) / sum f(s - c)
// over the samples s of the pixels within the filter's reach of p (its own and
// its neighbours', never outside the full image), summed in a fixed order:
// neighbour rows top to bottom, columns left to right, samples in index order.
// Every sample is a pure function of (seed, pixel index in the full image,
// sample index): its position comes from the sampler (sampler.hpp) and its
// random numbers from a pcg32 seeded with those numbers (random.hpp). So a
// pixel's value depends on nothing but the seed and its neighbourhood:
//  - the image is bit-identical for any thread count, tile size and run;
//  - a crop (a sub-rectangle) has exactly the pixels of the full image there,
//    so crops rendered apart (other processes, other machines) paste together
//    into the full image bit for bit.
// The price of a filter wider than a pixel: each tile also computes the samples
// of the pixels in a border `filter_reach` wide around it, which neighbouring
// tiles compute again: ((t + 2 r)^2 - t^2) / t^2 more samples for t x t tiles
// and reach r (an eighth more for 32 x 32 tiles and reach 1; none for the
// default box filter).
//
// Tiles (squares of tile_size pixels, row by row) are handed to the threads by
// rt::parallel_for (parallel.hpp); each writes only its own pixels. With a
// progress callback the calling thread waits and calls it about 4 times a
// second. If a tile throws (a bad scene, an unfinished exercise), the others
// stop after their current tile and render() rethrows the first exception.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "filter.hpp"
#include "../core/image.hpp"
#include "../system/parallel.hpp"
#include "../core/random.hpp"
#include "../core/ray.hpp"
#include "sampler.hpp"
#include "../core/vec.hpp"

namespace rt {

/// A sub-rectangle of the image: columns [x0, x1) from the left, rows [y0, y1) from the top.
struct crop_window {
    int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
};

struct render_options {
    int width = 640;   ///< the full image, also when rendering a crop
    int height = 480;
    int samples_per_pixel = 1;                  ///< asked for; see effective_samples()
    sampler_kind sampler = sampler_kind::jittered;
    filter reconstruction{};                    ///< box of radius 1/2 by default
    int threads = 0;                            ///< 0: std::thread::hardware_concurrency()
    std::uint64_t seed = 0;
    std::optional<crop_window> crop;            ///< render only this part (the result has its size)
    int tile_size = 32;
};

/// What a radiance function knows about the sample it computes.
struct sample_context {
    int x = 0, y = 0;   ///< the pixel: column from the left, row from the top of the full image
    int sample = 0;     ///< the sample's index within its pixel
    vec2 film{0};       ///< the film position (pixels from the bottom-left corner)
    pcg32 rng;          ///< random numbers for this sample alone, seeded from (seed, pixel, sample)
    std::uint64_t rays = 0;  ///< rays traced beyond the camera ray: the radiance function adds them
};

/// Where a render is, for a progress display.
struct render_progress {
    std::size_t pixels_done = 0;
    std::size_t pixels_total = 0;
    std::uint64_t rays = 0;  ///< camera rays plus the rays radiance functions reported
    double seconds = 0;      ///< since the render started
};

/// What a finished render did.
struct render_stats {
    int width = 0, height = 0;       ///< of the rendered image (the crop, if any)
    int samples_per_pixel = 0;       ///< effective samples per pixel
    int threads = 0;
    std::size_t tiles = 0;
    std::uint64_t camera_rays = 0;   ///< radiance evaluations, including the tiles' borders
    std::uint64_t extra_rays = 0;    ///< rays reported through sample_context::rays
    double seconds = 0;
};

struct render_result {
    image pixels;
    render_stats stats;
};

using progress_callback = std::function<void(const render_progress&)>;

/// The stream of the pcg32 a radiance function gets (sampler_stream places the samples).
constexpr std::uint64_t integrator_stream = 0x1a7e6a7011ull;

/// Throws rt::error (one line) unless the options describe a render that can run.
inline void check_render_options(const render_options& o)
{
    auto fail = [](const std::string& expected, const std::string& found) {
        throw make_error(source_location{"render options"}, expected, found);
    };
    if (o.width < 1 || o.height < 1)
        fail("an image of at least 1x1 pixels", std::to_string(o.width) + "x" + std::to_string(o.height));
    if (o.samples_per_pixel < 1)
        fail("at least 1 sample per pixel", std::to_string(o.samples_per_pixel));
    if (o.tile_size < 1 || o.tile_size > 4096)
        fail("a tile size from 1 to 4096 pixels", std::to_string(o.tile_size));
    if (!(o.reconstruction.radius > 0) || !(o.reconstruction.radius <= 16))
        fail("a filter radius in (0, 16] pixels", std::to_string(o.reconstruction.radius));
    const crop_window area = o.crop.value_or(crop_window{0, o.width, 0, o.height});
    const std::int64_t max_pixels = std::int64_t(1) << 28;
    if (std::int64_t(area.x1 - area.x0) * std::int64_t(area.y1 - area.y0) > max_pixels)
        fail("at most " + std::to_string(max_pixels) + " pixels to render (use --crop to split the image)",
             std::to_string(area.x1 - area.x0) + "x" + std::to_string(area.y1 - area.y0));
    if (o.crop) {
        const crop_window& c = *o.crop;
        if (c.x0 < 0 || c.y0 < 0 || c.x1 > o.width || c.y1 > o.height || c.x0 >= c.x1 || c.y0 >= c.y1)
            fail("a crop 0 <= x0 < x1 <= " + std::to_string(o.width) + ", 0 <= y0 < y1 <= " +
                     std::to_string(o.height),
                 "x0 x1 y0 y1 = " + std::to_string(c.x0) + " " + std::to_string(c.x1) + " " + std::to_string(c.y0) +
                     " " + std::to_string(c.y1));
    }
}

/// Copies `piece` into `full` with its top-left pixel at column x0, row y0 (merging crops).
inline void paste(image& full, const image& piece, int x0, int y0)
{
    if (x0 < 0 || y0 < 0 || x0 + piece.width > full.width || y0 + piece.height > full.height)
        throw error("paste: expected the piece inside the image, found a " + std::to_string(piece.width) + "x" +
                    std::to_string(piece.height) + " piece at (" + std::to_string(x0) + ", " + std::to_string(y0) +
                    ") in a " + std::to_string(full.width) + "x" + std::to_string(full.height) + " image");
    for (int y = 0; y < piece.height; ++y)
        for (int x = 0; x < piece.width; ++x)
            full.at(x0 + x, y0 + y) = piece.at(x, y);
}

namespace detail {

struct tile_rect {
    int x0, x1, y0, y1; ///< in full-image pixels, columns from the left, rows from the top
};

/// A worker's buffers, kept from tile to tile so that memory is not
/// allocated (and page-faulted in) again for every tile. Each on cache lines
/// of its own: two workers' scratch side by side in one line (96 bytes each)
/// wrote each other's line at every pixel (false sharing), and whether they
/// did depended on where malloc put the array: whole frames on two threads
/// were 1.50-1.57x one thread in one process and 1.92-1.97x in another
/// (docs/performance.md, experiment 7).
struct alignas(64) tile_scratch {
    std::vector<color> radiances;
    std::vector<double> weight_x, weight_y;
    std::vector<vec2> offsets;
};

/// Renders one tile into `out` (whose top-left pixel is the full image's (origin_x, origin_y)).
///
/// Two passes. First every sample of the tile and its border: its radiance,
/// and its filter weights f(dx) and f(dy) for each of the 2 reach + 1 columns
/// and rows of pixel centres it can touch (the filter is separable, so the
/// (2 reach + 1)^2 weights of a sample are products of these; computing them
/// once per sample instead of once per sample and pixel saves most of the
/// filtering work of a wide filter). Then each pixel's weighted average.
template <class RaySource, class Radiance>
std::uint64_t render_tile(const render_options& o, const tile_rect& tile, const RaySource& ray_at,
                          const Radiance& radiance, image& out, int origin_x, int origin_y,
                          tile_scratch& scratch, std::uint64_t& extra_rays)
{
    const int reach = filter_reach(o.reconstruction);
    const std::size_t span = std::size_t(2 * reach + 1);
    const int spp = effective_samples(o.sampler, o.samples_per_pixel);
    // the pixels whose samples this tile needs: the tile and a border, inside the full image
    const int qx0 = std::max(0, tile.x0 - reach), qx1 = std::min(o.width, tile.x1 + reach);
    const int qy0 = std::max(0, tile.y0 - reach), qy1 = std::min(o.height, tile.y1 + reach);
    const std::size_t region_width = std::size_t(qx1 - qx0);
    const std::size_t count = region_width * std::size_t(qy1 - qy0) * std::size_t(spp);
    std::vector<color>& radiances = scratch.radiances;
    std::vector<double>& weight_x = scratch.weight_x;
    std::vector<double>& weight_y = scratch.weight_y;
    std::vector<vec2>& offsets = scratch.offsets;
    radiances.resize(count); // every entry is written below before it is read
    weight_x.resize(count * span);
    weight_y.resize(count * span);
    auto first_sample = [&](int qx, int qy) {
        return (std::size_t(qy - qy0) * region_width + std::size_t(qx - qx0)) * std::size_t(spp);
    };
    std::uint64_t camera_rays = 0;
    for (int qy = qy0; qy < qy1; ++qy) {
        const int row_from_bottom = o.height - 1 - qy;
        for (int qx = qx0; qx < qx1; ++qx) {
            const std::uint64_t pixel_index = std::uint64_t(qy) * std::uint64_t(o.width) + std::uint64_t(qx);
            pixel_samples(o.sampler, o.samples_per_pixel, o.seed, pixel_index, offsets);
            for (int k = 0; k < spp; ++k) {
                const std::size_t n = first_sample(qx, qy) + std::size_t(k);
                sample_context ctx{qx, qy, k, vec2(real(qx) + offsets[std::size_t(k)].x,
                                                   real(row_from_bottom) + offsets[std::size_t(k)].y),
                                   seeded_generator(o.seed, pixel_index, std::uint64_t(k) + 1, integrator_stream), 0};
                radiances[n] = radiance(ray_at(ctx.film.x, ctx.film.y), ctx);
                extra_rays += ctx.rays;
                ++camera_rays;
                // weights towards the centres of pixel columns qx - reach + j and
                // rows qy - reach + j (rows count from the top, the film from the bottom)
                for (std::size_t j = 0; j < span; ++j) {
                    const int px = qx - reach + int(j), py = qy - reach + int(j);
                    weight_x[n * span + j] = filter_value(o.reconstruction, double(ctx.film.x) - (double(px) + 0.5));
                    weight_y[n * span + j] =
                        filter_value(o.reconstruction, double(ctx.film.y) - (double(o.height - 1 - py) + 0.5));
                }
            }
        }
    }
    // each pixel's weighted average over its neighbourhood, in a fixed order
    for (int py = tile.y0; py < tile.y1; ++py)
        for (int px = tile.x0; px < tile.x1; ++px) {
            double sum_r = 0, sum_g = 0, sum_b = 0, sum_w = 0;
            for (int qy = std::max(qy0, py - reach); qy < std::min(qy1, py + reach + 1); ++qy)
                for (int qx = std::max(qx0, px - reach); qx < std::min(qx1, px + reach + 1); ++qx) {
                    const std::size_t jx = std::size_t(px - qx + reach), jy = std::size_t(py - qy + reach);
                    for (std::size_t n = first_sample(qx, qy), end = n + std::size_t(spp); n < end; ++n) {
                        const double w = weight_x[n * span + jx] * weight_y[n * span + jy];
                        if (w == 0)
                            continue;
                        sum_r += w * double(radiances[n].r);
                        sum_g += w * double(radiances[n].g);
                        sum_b += w * double(radiances[n].b);
                        sum_w += w;
                    }
                }
            // sum_w > 0 for box, tent and Gaussian; for Mitchell-Netravali in
            // practice (each own sample weighs at least 0.28, a neighbour's at
            // worst -0.033). A sum of 0 (no sample counts) gives black.
            const color value = sum_w != 0 ? color(float(sum_r / sum_w), float(sum_g / sum_w), float(sum_b / sum_w))
                                           : color(0.0f);
            out.at(px - origin_x, py - origin_y) = value;
        }
    return camera_rays;
}

} // namespace detail

/// Renders the image (or options.crop of it): see the header comment.
/// `ray_at(real x, real y) -> ray` and `radiance(const ray&, sample_context&) -> color`
/// are called concurrently from options.threads threads.
template <class RaySource, class Radiance>
render_result render(const render_options& options, const RaySource& ray_at, const Radiance& radiance,
                     const progress_callback& progress = {})
{
    check_render_options(options);
    const crop_window area = options.crop.value_or(crop_window{0, options.width, 0, options.height});
    const int area_width = area.x1 - area.x0, area_height = area.y1 - area.y0;
    const int t = options.tile_size;
    std::vector<detail::tile_rect> tiles;
    for (int y = area.y0; y < area.y1; y += t)
        for (int x = area.x0; x < area.x1; x += t)
            tiles.push_back({x, std::min(x + t, area.x1), y, std::min(y + t, area.y1)});

    render_result result;
    result.pixels = image(area_width, area_height);
    const int threads = std::min(thread_count(options.threads), int(tiles.size()));

    std::atomic<std::size_t> pixels_done{0};
    std::atomic<std::uint64_t> camera_rays{0};
    std::atomic<std::uint64_t> extra_rays{0};
    const auto start = std::chrono::steady_clock::now();
    auto seconds_since_start = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    const std::size_t pixels_total = std::size_t(area_width) * std::size_t(area_height);
    auto snapshot = [&] {
        return render_progress{pixels_done.load(), pixels_total, camera_rays.load() + extra_rays.load(),
                               seconds_since_start()};
    };

    std::vector<detail::tile_scratch> scratch(static_cast<std::size_t>(threads)); // one per worker
    parallel_for(
        tiles.size(), threads,
        [&](std::size_t index, int worker) {
            const detail::tile_rect& tile = tiles[index];
            std::uint64_t extra = 0;
            const std::uint64_t camera = detail::render_tile(options, tile, ray_at, radiance, result.pixels, area.x0,
                                                             area.y0, scratch[std::size_t(worker)], extra);
            camera_rays.fetch_add(camera);
            extra_rays.fetch_add(extra);
            pixels_done.fetch_add(std::size_t(tile.x1 - tile.x0) * std::size_t(tile.y1 - tile.y0));
        },
        progress ? std::function<void()>([&] { progress(snapshot()); }) : std::function<void()>());
    if (progress)
        progress(snapshot());

    render_stats& stats = result.stats;
    stats.width = area_width;
    stats.height = area_height;
    stats.samples_per_pixel = effective_samples(options.sampler, options.samples_per_pixel);
    stats.threads = threads;
    stats.tiles = tiles.size();
    stats.camera_rays = camera_rays.load();
    stats.extra_rays = extra_rays.load();
    stats.seconds = seconds_since_start();
    return result;
}

} // namespace rt
