// byte_level.hpp - the 256 levels of an 8-bit channel, k / 255, and the
// rounding to the nearest one that every 8-bit writer shares: the early
// stages' to_byte (image_io.hpp) and the stage-08 pipeline's quantize
// (encoding.hpp), each with its own rule for values outside [0, 1].
#pragma once

#include <cstdint>

namespace rt {

/// Given (not an exercise): the nearest of the 256 levels k / 255 to a value v
/// that is already in [0, 1], halves rounded up: round(255 v). v * 255 + 0.5
/// is in [0.5, 255.5], and the conversion truncates. The caller keeps v in
/// [0, 1] (and not NaN): the stage-08 exercise quantize below, and the early
/// stages' to_byte (image_io.hpp), each with its own rule for other values.
inline std::uint8_t nearest_byte_level(float v)
{
    return std::uint8_t(v * 255.0f + 0.5f);
}

} // namespace rt
