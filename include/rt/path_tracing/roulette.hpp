// roulette.hpp - Russian roulette: ending paths without bias (stage 11).
//
// A path could bounce for ever; cutting it after a fixed number of bounces
// loses the light of the longer paths (the image is too dark). Russian
// roulette (J. Arvo, D. Kirk, "Particle Transport and Image Synthesis",
// SIGGRAPH 1990; PBR 4th ed., sec. 2.2.4) ends it at random instead: the path
// goes on with a probability q and its throughput is divided by q, so the
// expected value is unchanged,
//     E = q (throughput / q) + (1 - q) 0 = throughput,
// while paths that carry little light are ended more often. As pbrt-v4's path
// tracer (sec. 13.4), q is the throughput's largest component, at most 1, and
// the roulette starts only after a few bounces: the first bounces carry most
// of the light, and ending them early adds noise for little time saved.
//
//     if (!rt::russian_roulette(throughput, bounce, start, xi)) break;
#pragma once

#include <algorithm>

#include "../core/config.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The bounce from which paths play Russian roulette, as PBR 4th ed.'s path tracer.
constexpr int roulette_start = 3;

/// Russian roulette for a path after `bounce` bounces (bounce >= start: it
/// plays; before: it always goes on, its throughput unchanged). It goes on
/// with the probability q = min(1, largest component of throughput), when the
/// uniform number xi in [0, 1) is below q, and its throughput is then divided
/// by q. Returns whether the path goes on.
inline bool russian_roulette(color& throughput, int bounce, int start, real xi)
{
    // RT_EXERCISE_BEGIN(stage11: Russian roulette)
    if (bounce < start)
        return true;
    const real q = std::min(real(1), real(std::max(throughput.r, std::max(throughput.g, throughput.b))));
    if (!(xi < q))
        return false;
    throughput /= float(q);
    return true;
    // RT_EXERCISE_END
}

} // namespace rt
