// sampler.hpp - where in a pixel to shoot the rays (antialiasing, stage 08).
//
// One ray through each pixel centre samples the image below its Nyquist rate,
// so edges stair-step and fine patterns alias. Several samples per pixel,
// placed well, estimate the pixel's average instead. A sampler gives the
// offsets (ox, oy) in [0, 1)^2 of a pixel's samples, measured like the film
// position from the pixel's bottom-left corner. References: Physically Based
// Rendering, 4th ed. (Pharr, Jakob, Humphreys), ch. 8 (sec. 8.5 stratified,
// 8.6 Halton); Fundamentals of Computer Graphics, 4th ed., sec. 13.4.1.
//
//   center    one sample at (1/2, 1/2); spp is ignored (the stages-02-07 image).
//   grid      an nx x ny grid of cell centres ((a + 1/2)/nx, (b + 1/2)/ny).
//   random    spp independent uniform points.
//   jittered  one uniform point in each cell of the nx x ny grid
//             ((a + u)/nx, (b + v)/ny): stratified sampling.
//   halton    the first spp points of the 2D Halton sequence (radical inverses
//             in bases 2 and 3: J. H. Halton, "On the efficiency of certain
//             quasi-random sequences of points in evaluating multi-dimensional
//             integrals", Numerische Mathematik 2, 1960), made different in every
//             pixel by random digit scrambling: each base-b digit position k gets
//             its own random permutation of {0, ..., b-1} (PBR 4th ed., sec. 8.6,
//             "random digit permutations").
//             Permuting digits keeps the sequence's stratification: the first
//             2^k points have one x in each interval [m/2^k, (m+1)/2^k), the
//             first 3^k points one y in each [m/3^k, (m+1)/3^k).
//
// Grid and jittered with a samples-per-pixel count that is not a square use
// nx = ceil(sqrt(spp)) columns and ny = ceil(spp / nx) rows, i.e. at least spp
// and fewer than spp + nx samples: 2 -> 2x1, 5 -> 3x2, 8 -> 3x3, 12 -> 4x3.
// effective_samples() gives the count actually used; the renderer reports it.
//
// Every random number comes from a pcg32 seeded from (seed, pixel index)
// (random.hpp): a pixel's samples are the same whichever thread or tile asks.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "../core/enum_names.hpp"
#include "../core/random.hpp"
#include "../core/vec.hpp"

namespace rt {

enum class sampler_kind { center, grid, random, jittered, halton };

/// The grid the grid and jittered samplers use for spp samples (see the header comment).
struct grid_shape {
    int columns = 1;  ///< nx = ceil(sqrt(spp))
    int rows = 1;     ///< ny = ceil(spp / nx)
};

inline grid_shape grid_shape_for(int spp)
{
    grid_shape grid;
    if (spp <= 1)
        return grid;
    while (grid.columns * grid.columns < spp) // ceil(sqrt(spp)) in exact integers
        ++grid.columns;
    grid.rows = (spp + grid.columns - 1) / grid.columns;
    return grid;
}

/// The number of samples a pixel really gets when `spp` are asked for.
inline int effective_samples(sampler_kind kind, int spp)
{
    spp = std::max(spp, 1);
    switch (kind) {
    case sampler_kind::center: return 1;
    case sampler_kind::grid:
    case sampler_kind::jittered: {
        const grid_shape grid = grid_shape_for(spp);
        return grid.columns * grid.rows;
    }
    case sampler_kind::random:
    case sampler_kind::halton: break;
    }
    return spp;
}

/// The radical inverse of `index` in `base`: its base-b digits mirrored about
/// the point, 0.d1 d2 d3 ... for index = ... d3 d2 d1 (Halton 1960).
inline double radical_inverse(unsigned base, std::uint32_t index)
{
    double result = 0, scale = 1.0 / base;
    for (; index > 0; index /= base, scale /= base)
        result += (index % base) * scale;
    return result;
}

namespace detail {

/// The largest value below 1 of type real, so that offsets stay inside [0, 1).
inline real below_one(double x)
{
    const real r = real(x);
    const real largest = std::nextafter(real(1), real(0));
    return r < largest ? r : largest;
}

/// Base 2 with random digit scrambling: flipping digit k (a permutation of
/// {0, 1}) is an exclusive-or of bit k of the mirrored index with the mask.
inline double scrambled_radical_inverse_2(std::uint32_t index, std::uint32_t flips)
{
    std::uint32_t mirrored = 0;
    for (int bit = 0; bit < 32; ++bit)
        mirrored |= ((index >> bit) & 1u) << (31 - bit);
    return double(mirrored ^ flips) * (1.0 / 4294967296.0);
}

/// The number of base-3 digits scrambled: 3^20 > the largest samples per pixel.
constexpr int base3_digits = 20;

/// Base 3 with random digit scrambling: digit k of the mirrored index goes
/// through permutation number choice[k] of the six permutations of {0, 1, 2};
/// the trailing zero digits are permuted too (that is what moves the points).
inline double scrambled_radical_inverse_3(std::uint32_t index, const std::array<std::uint8_t, base3_digits>& choice)
{
    static constexpr std::uint8_t permutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                                        {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    double result = 0, scale = 1.0 / 3;
    for (int k = 0; k < base3_digits; ++k, index /= 3, scale /= 3)
        result += permutations[choice[std::size_t(k)]][index % 3] * scale;
    return result;
}

} // namespace detail

/// The stream of the pcg32 that places a pixel's samples (random.hpp).
constexpr std::uint64_t sampler_stream = 0x5a3c0ffee1ull;

/// Replaces `offsets` by the sample offsets in [0, 1)^2 of pixel `pixel_index`
/// for a render with `seed`; effective_samples(kind, spp) of them.
inline void pixel_samples(sampler_kind kind, int spp, std::uint64_t seed, std::uint64_t pixel_index,
                          std::vector<vec2>& offsets)
{
    offsets.clear();
    spp = std::max(spp, 1);
    pcg32 rng = seeded_generator(seed, pixel_index, 0, sampler_stream);
    switch (kind) {
    case sampler_kind::center:
        offsets.emplace_back(real(0.5), real(0.5));
        return;
    case sampler_kind::grid:
    case sampler_kind::jittered: {
        const grid_shape grid = grid_shape_for(spp);
        const bool jitter = kind == sampler_kind::jittered;
        for (int b = 0; b < grid.rows; ++b)
            for (int a = 0; a < grid.columns; ++a) {
                const double u = jitter ? double(rng.next_float()) : 0.5;
                const double v = jitter ? double(rng.next_float()) : 0.5;
                offsets.emplace_back(detail::below_one((a + u) / grid.columns),
                                     detail::below_one((b + v) / grid.rows));
            }
        return;
    }
    case sampler_kind::random:
        for (int k = 0; k < spp; ++k) {
            const real u = real(rng.next_float());
            offsets.emplace_back(u, real(rng.next_float()));
        }
        return;
    case sampler_kind::halton: {
        const std::uint32_t flips = rng.next_u32();
        std::array<std::uint8_t, detail::base3_digits> choice{};
        for (std::uint8_t& c : choice)
            c = std::uint8_t(rng.next_below(6));
        for (int k = 0; k < spp; ++k)
            offsets.emplace_back(detail::below_one(detail::scrambled_radical_inverse_2(std::uint32_t(k), flips)),
                                 detail::below_one(detail::scrambled_radical_inverse_3(std::uint32_t(k), choice)));
        return;
    }
    }
}

/// The names of the samplers; the first is the default.
inline constexpr detail::enum_name<sampler_kind> sampler_names[] = {
    {sampler_kind::center, "center"}, {sampler_kind::grid, "grid"},     {sampler_kind::random, "random"},
    {sampler_kind::jittered, "jittered"}, {sampler_kind::halton, "halton"}};

/// The sampler a name means ("center", "grid", "random", "jittered", "halton"), or nothing.
inline std::optional<sampler_kind> sampler_from_name(const std::string& name)
{
    return detail::value_named(sampler_names, name);
}

inline const char* name_of(sampler_kind kind) { return detail::name_in(sampler_names, kind); }

/// The sampler used when none is named: one ray through each pixel centre for
/// 1 sample per pixel (the image of stages 02-07), jittered otherwise.
inline sampler_kind default_sampler(int samples_per_pixel)
{
    return samples_per_pixel == 1 ? sampler_kind::center : sampler_kind::jittered;
}

} // namespace rt
