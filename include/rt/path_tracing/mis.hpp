// mis.hpp - four ways to light a path, and multiple importance sampling (stage 11).
//
// A path tracer can find the light a point receives directly in two ways:
// BSDF sampling (the next direction of the path meets an emitter, and its
// emission counts) and next-event estimation (a shadow ray to a random point
// of the emitters, next_event.hpp). Each is an unbiased estimate of the same
// direct light; using both and adding them counts it twice. The strategies:
//     uniform   BSDF sampling only, directions uniform over the hemisphere
//     cosine    BSDF sampling only, cosine-weighted directions (lambertian.hpp)
//     nee       next-event estimation for the emitters it can aim at; a path's
//               later hits on them add nothing (the camera ray's own hit still
//               counts: nothing aimed at it)
//     mis       both, each weighted by the power heuristic (E. Veach, "Robust
//               Monte Carlo Methods for Light Transport Simulation", PhD
//               thesis, Stanford 1997, sec. 9.2.4; PBR 4th ed., sec. 2.2.3):
//                   w_a = pdf_a^2 / (pdf_a^2 + pdf_b^2)
//               for the sample of strategy a, pdf_b the density the other
//               strategy has for the same direction; the two weights of a
//               direction add up to 1, so nothing is counted twice.
// Emitters next-event estimation cannot aim at (glowing spheres, the
// background) count fully when a path meets them, whatever the strategy.
//
//     L += throughput * rt::emission_weight(strategy, bounce, sampled, pdf_bsdf, pdf_light) * Le;
//     L += throughput * rt::light_sample_weight(strategy, pdf_light, pdf_bsdf) * direct;
#pragma once

#include "../core/config.hpp"
#include "../core/enum_names.hpp"

namespace rt {

enum class path_strategy { uniform, cosine, nee, mis };

inline constexpr detail::enum_name<path_strategy> path_strategy_names[] = {
    {path_strategy::uniform, "uniform"}, {path_strategy::cosine, "cosine"}, {path_strategy::nee, "nee"},
    {path_strategy::mis, "mis"}};

inline const char* name_of(path_strategy kind) { return detail::name_in(path_strategy_names, kind); }

/// True for the strategies that trace a shadow ray to the emitters at each bounce.
inline bool samples_lights(path_strategy kind)
{
    return kind == path_strategy::nee || kind == path_strategy::mis;
}

/// The power heuristic with beta = 2, one sample of each strategy (Veach 1997,
/// sec. 9.2.4): pdf_a^2 / (pdf_a^2 + pdf_b^2); 0 when both densities are 0.
inline real power_heuristic(real pdf_a, real pdf_b)
{
    // RT_EXERCISE_BEGIN(stage11: the power heuristic)
    const real a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    if (!(a + b > 0))
        return 0;
    return a / (a + b);
    // RT_EXERCISE_END
}

/// The weight of the emission Le that a path meets after `bounce` bounces
/// (0: the camera ray's own hit), for `strategy`. `sampled` says whether
/// next-event estimation can aim at that emitter (emitters.hpp); pdf_bsdf is
/// the density of the direction the path took to get there, pdf_light the
/// density next-event estimation has for that direction (both per unit solid angle).
inline real emission_weight(path_strategy strategy, int bounce, bool sampled, real pdf_bsdf, real pdf_light)
{
    // RT_EXERCISE_BEGIN(stage11: counting emission once)
    if (bounce == 0 || !sampled || !samples_lights(strategy))
        return 1;
    if (strategy == path_strategy::nee)
        return 0; // next-event estimation counted it already
    return power_heuristic(pdf_bsdf, pdf_light);
    // RT_EXERCISE_END
}

/// The weight of a next-event estimate (a shadow ray's light) for `strategy`:
/// pdf_light is the density of its direction for next-event estimation,
/// pdf_bsdf the density BSDF sampling has for it.
inline real light_sample_weight(path_strategy strategy, real pdf_light, real pdf_bsdf)
{
    // RT_EXERCISE_BEGIN(stage11: weighting the light sample)
    if (strategy == path_strategy::nee)
        return 1;
    if (strategy == path_strategy::mis)
        return power_heuristic(pdf_light, pdf_bsdf);
    return 0; // BSDF sampling alone traces no shadow ray
    // RT_EXERCISE_END
}

} // namespace rt
