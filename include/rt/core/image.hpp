// image.hpp - a 2D buffer of linear RGB floats.
//
// Stored row by row, top row first, as image files store them. The book counts
// pixel rows j from the bottom: pixel (i, j) is at(i, height - 1 - j).
#pragma once

#include <cstddef>
#include <vector>

#include "vec.hpp"

namespace rt {

struct image {
    int width = 0;
    int height = 0;
    std::vector<color> pixels; ///< width * height colors, top row first

    image() = default;
    image(int w, int h, color fill = color(0))
        : width(w), height(h), pixels(std::size_t(w) * std::size_t(h), fill) {}

    /// The pixel in column x (from the left) and row y (from the top).
    color& at(int x, int y) { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
    const color& at(int x, int y) const { return pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

} // namespace rt
