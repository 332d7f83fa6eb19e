// filter.hpp - reconstruction filters: how much each sample counts in a pixel (stage 08).
//
// A pixel's value is the weighted average of the samples around its centre c:
//     I(p) = sum_k f(s_k - c) L_k / sum_k f(s_k - c)
// over every sample s_k (with radiance L_k) within the filter's radius, its own
// and its neighbours' (Physically Based Rendering, 4th ed., sec. 8.8 "Image
// Reconstruction"; Fundamentals of Computer Graphics, 4th ed., ch. 9 on
// filters and sampling). The 2D filter is separable: f(x, y) = f(x) f(y), with
// f(x) = 0 for |x| >= radius. Dividing by the sum of the weights normalises
// them, so a constant image stays constant whatever the filter.
//
//   box       f(x) = 1                                   default radius 1/2
//   tent      f(x) = 1 - |x| / r                         default radius 1
//   gaussian  f(x) = exp(-x^2 / (2 s^2)) - exp(-r^2 / (2 s^2)), s = r / 3
//             (shifted down so that it reaches 0 at the radius, as PBR 4th
//             ed., sec. 8.8, does)                       default radius 3/2
//   mitchell  f(x) = k(2 x / r), k the cubic of D. P. Mitchell, A. N. Netravali,
//             "Reconstruction Filters in Computer Graphics", SIGGRAPH 1988, eq. 8,
//             with B = C = 1/3 (their recommendation):
//               k(x) = 1/6 [(12 - 9B - 6C)|x|^3 + (-18 + 12B + 6C)|x|^2 + (6 - 2B)]          |x| < 1
//               k(x) = 1/6 [(-B - 6C)|x|^3 + (6B + 30C)|x|^2 + (-12B - 48C)|x| + (8B + 24C)] 1 <= |x| < 2
//             It dips below 0 between 1 and 2 (sharpening; a dark ring can
//             appear beside a very bright edge)           default radius 2
//
// Integrals over the line, used by the tests (worked out by hand):
//   box 2r, tent r, mitchell r / 2 (k integrates to 1 for every B, C),
//   gaussian s sqrt(2 pi) erf(r / (s sqrt 2)) - 2 r exp(-r^2 / (2 s^2)).
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "../core/enum_names.hpp"
#include "../core/vec.hpp"

namespace rt {

enum class filter_kind { box, tent, gaussian, mitchell };

/// The radius a filter kind has unless one is given (see the header comment).
inline real default_radius(filter_kind kind)
{
    switch (kind) {
    case filter_kind::tent: return real(1);
    case filter_kind::gaussian: return real(1.5);
    case filter_kind::mitchell: return real(2);
    case filter_kind::box: break;
    }
    return real(0.5);
}

struct filter {
    filter_kind kind = filter_kind::box;
    real radius = real(0.5);  ///< f(x) = 0 for |x| >= radius, in pixels
};

inline filter make_filter(filter_kind kind, std::optional<real> radius = std::nullopt)
{
    return filter{kind, radius.value_or(default_radius(kind))};
}

/// The Mitchell-Netravali cubic k(x) of eq. 8 (support |x| < 2).
inline double mitchell_netravali(double x, double B, double C)
{
    x = std::fabs(x);
    if (x < 1)
        return ((12 - 9 * B - 6 * C) * x * x * x + (-18 + 12 * B + 6 * C) * x * x + (6 - 2 * B)) / 6;
    if (x < 2)
        return ((-B - 6 * C) * x * x * x + (6 * B + 30 * C) * x * x + (-12 * B - 48 * C) * x + (8 * B + 24 * C)) / 6;
    return 0;
}

/// The 1D filter f(x) at a distance x (pixels) from the pixel centre.
inline double filter_value(const filter& f, double x)
{
    const double r = f.radius;
    const double ax = std::fabs(x);
    if (!(ax < r))
        return 0;
    switch (f.kind) {
    case filter_kind::box: return 1;
    case filter_kind::tent: return 1 - ax / r;
    case filter_kind::gaussian:
        // s = r / 3, so x^2 / (2 s^2) = 4.5 (x / r)^2 and the value at the radius is exp(-4.5)
        return std::exp(-4.5 * (x / r) * (x / r)) - std::exp(-4.5);
    case filter_kind::mitchell: return mitchell_netravali(2 * x / r, 1.0 / 3, 1.0 / 3);
    }
    return 0;
}

/// The 2D weight f(dx) f(dy) of a sample at (dx, dy) from the pixel centre.
inline double filter_weight(const filter& f, double dx, double dy)
{
    return filter_value(f, dx) * filter_value(f, dy);
}

/// The integral of the 1D filter over the line, in closed form (see the header comment).
inline double filter_integral(const filter& f)
{
    const double r = f.radius;
    switch (f.kind) {
    case filter_kind::box: return 2 * r;
    case filter_kind::tent: return r;
    case filter_kind::gaussian: {
        const double s = r / 3;
        const double pi = 3.14159265358979323846;
        return s * std::sqrt(2 * pi) * std::erf(r / (s * std::sqrt(2.0))) - 2 * r * std::exp(-r * r / (2 * s * s));
    }
    case filter_kind::mitchell: return r / 2;
    }
    return 0;
}

/// How many pixels beyond its own a pixel's filter reaches: samples of pixel q
/// lie in [q, q + 1), so they can touch pixel p's centre p + 1/2 within the
/// radius only if |q - p| <= ceil(radius - 1/2).
inline int filter_reach(const filter& f)
{
    const double reach = std::ceil(double(f.radius) - 0.5);
    return reach > 0 ? int(reach) : 0;
}

/// The names of the filters; the first is the default.
inline constexpr detail::enum_name<filter_kind> filter_names[] = {
    {filter_kind::box, "box"}, {filter_kind::tent, "tent"}, {filter_kind::gaussian, "gaussian"},
    {filter_kind::mitchell, "mitchell"}};

/// The filter a name means ("box", "tent", "gaussian", "mitchell"), or nothing.
inline std::optional<filter_kind> filter_from_name(const std::string& name) { return detail::value_named(filter_names, name); }

inline const char* name_of(filter_kind kind) { return detail::name_in(filter_names, kind); }

} // namespace rt
