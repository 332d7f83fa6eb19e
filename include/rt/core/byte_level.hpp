// byte_level.hpp - the 256 levels of an 8-bit channel, k / 255 (stage 02).
//
// The course: "RGB floats internally, RGB bytes stored". Every 8-bit writer
// ends here: the early stages' to_byte (image_io.hpp, after a plain gamma) and
// stage 08's color pipeline (encoding.hpp, after the tone map and sRGB) both
// store quantize(v) of their encoded value v. Rounding to the nearest level
// reaches every level exactly and errs by at most half a level.
#pragma once

#include <cstdint>

#include "error.hpp" // rt::exercise_not_done, thrown by the student kit's unfinished exercises

namespace rt {

/// Given (not an exercise): the nearest of the 256 levels k / 255 to a value v
/// that is already in [0, 1], halves rounded up: round(255 v). v * 255 + 0.5
/// is in [0.5, 255.5], and the conversion truncates. The caller keeps v in
/// [0, 1] (and not NaN): quantize below does.
inline std::uint8_t nearest_byte_level(float v)
{
    return std::uint8_t(v * 255.0f + 0.5f);
}

/// An encoded value in [0, 1] to one of the 256 byte levels: round(255 v),
/// halves rounded up; values below 0 (and NaN) give 0, above 1 give 255.
inline std::uint8_t quantize(float v)
{
    // RT_EXERCISE_BEGIN(stage02: quantise to 8 bits)
    // Hint: the given nearest_byte_level(v) rounds a v already in [0, 1]; the
    //   task is every other value: below 0, NaN, above 1.
    if (!(v > 0.0f)) // NaN fails this comparison too
        return 0;
    if (v >= 1.0f)
        return 255;
    return nearest_byte_level(v);
    // RT_EXERCISE_END
}

} // namespace rt
