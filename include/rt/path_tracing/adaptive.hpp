// adaptive.hpp - per-pixel adaptive sampling: stop when the pixel is known well enough (stage 11).
//
// Some pixels converge in a few samples (a flat wall in full light), others
// need thousands (a soft shadow's edge). Adaptive sampling spends samples
// where they are needed: a pixel takes its samples in batches, and after each
// batch the confidence interval of its mean decides whether it stops
// (UC Berkeley CS184/284A, Project 3-1 "PathTracer", Part 5, "Adaptive
// Sampling"). Over the n samples so far of the pixel's illuminance x_k
// (luminance below), with s1 = sum x_k and s2 = sum x_k^2:
//     mu = s1 / n,   sigma^2 = (s2 - s1^2 / n) / (n - 1),
//     I = 1.96 sigma / sqrt(n),
// the half-width of the confidence interval of level 0.95 of the mean (the
// central limit theorem). The pixel has converged when I <= max_tolerance mu:
// the true mean lies, at that level, within max_tolerance of mu, relatively.
//
//     rt::pixel_statistics stats; stats.add(rt::luminance(L));
//     if (n % batch == 0 && rt::pixel_converged(stats, max_tolerance)) stop;
#pragma once

#include <algorithm>
#include <cmath>

#include "../core/config.hpp"
#include "../core/vec.hpp"

namespace rt {

/// The luminance of a linear RGB color (Rec. 709 / sRGB primaries, ITU-R BT.709):
/// the "illuminance" CS184's adaptive sampling tests.
inline double luminance(const color& c)
{
    return 0.2126 * double(c.r) + 0.7152 * double(c.g) + 0.0722 * double(c.b);
}

/// The running sums of a pixel's samples.
struct pixel_statistics {
    double s1 = 0;  ///< sum of x_k
    double s2 = 0;  ///< sum of x_k^2
    int n = 0;      ///< samples so far

    void add(double x)
    {
        s1 += x;
        s2 += x * x;
        ++n;
    }
};

/// Whether the pixel of these statistics has converged by CS184's rule:
/// I = 1.96 sigma / sqrt(n) <= max_tolerance mu, with the sample mean mu and
/// the sample standard deviation sigma (n - 1 in its denominator). With fewer
/// than two samples nothing is known of sigma: not converged.
inline bool pixel_converged(const pixel_statistics& stats, double max_tolerance)
{
    // RT_EXERCISE_BEGIN(stage11: the confidence interval of a pixel)
    if (stats.n < 2)
        return false;
    const double n = double(stats.n);
    const double mu = stats.s1 / n;
    const double variance = std::max(0.0, (stats.s2 - stats.s1 * stats.s1 / n) / (n - 1));
    const double interval = 1.96 * std::sqrt(variance) / std::sqrt(n);
    return interval <= max_tolerance * mu;
    // RT_EXERCISE_END
}

} // namespace rt
