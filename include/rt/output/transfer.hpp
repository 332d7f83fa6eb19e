// transfer.hpp - transfer functions: linear light to the non-linear values a display expects (stage 08).
//
// Displays do not respond linearly to the stored number; image files store
// values encoded by a transfer function so that the 256 byte levels are spread
// evenly for the eye. Viewers treat PNG and PPM files that carry no color
// information as sRGB.
//
//   sRGB (IEC 61966-2-1:1999, "Default RGB color space - sRGB"):
//       encode(x) = 12.92 x                   for x <= 0.0031308
//                   1.055 x^(1/2.4) - 0.055   otherwise
//       decode(v) = v / 12.92                 for v <= 0.04045
//                   ((v + 0.055) / 1.055)^2.4 otherwise
//   The two pieces meet at x = 0.0031308 (12.92 x = 0.04044994, the power
//   piece 0.04044991: a step of 3e-8, far below one byte level); the
//   whole curve is close to, but not the same as, a plain gamma of 2.2.
//
//   plain gamma: encode(x) = x^(1/gamma)   (gamma = 1 stores linear values)
#pragma once

#include <cmath>

#include "../core/error.hpp" // rt::exercise_not_done, thrown by the student kit's unfinished exercises

namespace rt {

/// The sRGB encoding of a linear value x in [0, 1] (IEC 61966-2-1).
inline float srgb_encode(float x)
{
    // RT_EXERCISE_BEGIN(stage08: sRGB encode)
    if (x <= 0.0031308f)
        return 12.92f * x;
    return 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
    // RT_EXERCISE_END
}

/// The inverse of srgb_encode: the linear value of an sRGB-encoded v in [0, 1].
inline float srgb_decode(float v)
{
    if (v <= 0.04045f)
        return v / 12.92f;
    return std::pow((v + 0.055f) / 1.055f, 2.4f);
}

/// A plain power-law encoding x^(1/gamma) of a linear x in [0, 1]; negatives and NaN give 0.
inline float gamma_encode(float x, float gamma)
{
    if (!(x > 0.0f))
        return 0.0f;
    return std::pow(x, 1.0f / gamma);
}

} // namespace rt
