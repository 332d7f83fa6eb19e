// pixel_sampling.hpp - several rays per pixel, and one color from them (stage 02).
//
// The course: "Create image plane - Sample positions on image plane - Create
// ray for each position", and "Camera and sampling: simple sampling and
// reconstruction". One ray through each pixel centre samples the image once
// per pixel, so an edge becomes a staircase; several samples per pixel,
// averaged, estimate how much of the pixel each side of the edge covers.
//
// Positions are film positions, in pixels from the bottom-left corner of the
// image (what rt::generate_ray takes): pixel (i, j) is the square
// [i, i + 1] x [j, j + 1], its centre (i + 1/2, j + 1/2).
//
//   jittered (stratified) sampling: cut the pixel into n x n strata (cells) and
//   put one uniform random point in each, cell (a, b) holding
//       (i + (a + xi1) / n, j + (b + xi2) / n),   xi1, xi2 uniform in [0, 1)
//   (Fundamentals of Computer Graphics, 4th ed., sec. 13.4.1 "Antialiasing",
//   the jittered sampling pseudocode; Physically Based Rendering, 4th ed.,
//   sec. 8.5 "Stratified Sampler").
//
//   box reconstruction: the pixel's value is the plain average of the values
//   of the samples inside its square (FCG 4th ed., sec. 13.4.1; PBR 4th ed.,
//   sec. 8.8, the box filter of radius 1/2).
//
// The library's renderer keeps its own samplers and filters (sampler.hpp,
// filter.hpp: more kinds, any sample count, filters wider than a pixel); these
// two are the teaching path, used by the stage-02 program and benchmark 1.
#pragma once

#include <cstddef>
#include <vector>

#include "../core/random.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The n x n jittered sample positions of pixel (i, j): one uniform point in
/// each of the n x n equal cells of the square [i, i + 1] x [j, j + 1], the
/// random numbers drawn from `rng` (two per sample, n >= 1). The same
/// generator state gives the same positions.
inline std::vector<vec2> jittered_samples(int i, int j, int n, pcg32& rng)
{
    // RT_EXERCISE_BEGIN(stage02: jittered samples in a pixel)
    // Hint: loop over the cells (a, b); draw xi1 and xi2 with rng.next_float(),
    //   one draw per statement, and place the sample by the formula at the top of this file.
    std::vector<vec2> positions;
    positions.reserve(std::size_t(n) * std::size_t(n));
    for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
            const real xi1 = real(rng.next_float()); // one draw per statement: a fixed order
            const real xi2 = real(rng.next_float());
            positions.emplace_back(real(i) + (real(a) + xi1) / real(n), real(j) + (real(b) + xi2) / real(n));
        }
    return positions;
    // RT_EXERCISE_END
}

/// The box reconstruction of pixel (i, j): the average of values[k] over the
/// samples k whose positions[k] lie in the pixel's square [i, i + 1] x
/// [j, j + 1]; samples outside count for nothing; black when none is inside.
/// Precondition: positions and values have the same size.
inline color box_reconstruct(int i, int j, const std::vector<vec2>& positions, const std::vector<color>& values)
{
    // RT_EXERCISE_BEGIN(stage02: box reconstruction of a pixel)
    // Hint: sum the values of the samples inside and count them; mind a pixel
    //   with none inside.
    color sum(0);
    int inside = 0;
    for (std::size_t k = 0; k < positions.size(); ++k) {
        const vec2 p = positions[k];
        if (real(i) <= p.x && p.x <= real(i + 1) && real(j) <= p.y && p.y <= real(j + 1)) {
            sum += values[k];
            ++inside;
        }
    }
    return inside > 0 ? sum / float(inside) : color(0);
    // RT_EXERCISE_END
}

} // namespace rt
