// tonemap.hpp - exposure and tone maps: linear radiance to display values in [0, 1] (stage 08).
//
// A renderer computes radiance, which has no upper bound; a display shows
// values in [0, 1]. The color pipeline (encoding.hpp) first scales by the
// exposure, then compresses [0, inf) into [0, 1] with a tone map, then encodes
// (transfer.hpp) and quantises. Each tone map here acts on one channel; applied
// to R, G and B separately, bright saturated colors drift towards white, which
// is the usual look of a per-channel curve.
//
//   exposure   c' = c 2^stops                      (photographic stops)
//   clamp      T(x) = min(max(x, 0), 1)
//   Reinhard   T(x) = x / (1 + x)                  Reinhard, Stark, Shirley, Ferwerda,
//                                                  "Photographic Tone Reproduction for Digital
//                                                  Images", SIGGRAPH 2002, eq. 3
//   ACES fit   T(x) = x(a x + b) / (x(c x + d) + e), clamped to [0, 1], with
//              a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14: K. Narkowicz, "ACES
//              Filmic Tone Mapping Curve" (2016, knarkowicz.wordpress.com), a fit of
//              the ACES reference rendering + output transforms, pre-exposed so that
//              T(1) is about 0.8.
//
// Every curve maps NaN and negative values to 0 and +inf to 1, so one bad
// sample can never become a black pixel in a bright area or the reverse.
#pragma once

#include <cmath>
#include "encoding_settings.hpp" // tonemap_kind and its names
#include "../core/error.hpp" // rt::exercise_not_done, thrown by the student kit's unfinished exercises
#include "../core/vec.hpp"

namespace rt {

/// The channel scaled by 2^stops: +1 stop doubles the light, -1 halves it.
inline color apply_exposure(const color& c, float stops)
{
    return c * std::exp2(stops);
}

/// Clamp: values above 1 are cut to 1 (the highlights burn out), negatives and NaN to 0.
inline float tonemap_clamp(float x)
{
    // RT_EXERCISE_BEGIN(stage08: clamp tone map)
    if (!(x > 0.0f)) // negative, zero or NaN
        return 0.0f;
    return x < 1.0f ? x : 1.0f;
    // RT_EXERCISE_END
}

/// Reinhard et al. 2002, eq. 3: T(x) = x / (1 + x). T(1) = 1/2, T(x) -> 1 as x -> inf.
inline float tonemap_reinhard(float x)
{
    // RT_EXERCISE_BEGIN(stage08: Reinhard tone map)
    if (!(x > 0.0f))
        return 0.0f;
    if (std::isinf(x)) // inf / inf would be NaN; the limit is 1
        return 1.0f;
    return x / (1.0f + x);
    // RT_EXERCISE_END
}

/// Narkowicz's fit of the ACES filmic curve: T(x) = x(a x + b) / (x(c x + d) + e), clamped to [0, 1].
inline float tonemap_aces(float x)
{
    // RT_EXERCISE_BEGIN(stage08: ACES filmic tone map)
    const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
    if (!(x > 0.0f))
        return 0.0f;
    if (std::isinf(x))
        return 1.0f;
    const float t = x * (a * x + b) / (x * (c * x + d) + e);
    return t < 1.0f ? t : 1.0f; // the curve tends to a / c = 1.033, so it is clamped
    // RT_EXERCISE_END
}

/// One channel through the named tone map.
inline float apply_tonemap(float x, tonemap_kind kind)
{
    switch (kind) {
    case tonemap_kind::reinhard: return tonemap_reinhard(x);
    case tonemap_kind::aces: return tonemap_aces(x);
    case tonemap_kind::clamp: break;
    }
    return tonemap_clamp(x);
}

/// Each channel of a color through the named tone map.
inline color apply_tonemap(const color& c, tonemap_kind kind)
{
    return color(apply_tonemap(c.r, kind), apply_tonemap(c.g, kind), apply_tonemap(c.b, kind));
}

} // namespace rt
