// rounding.hpp - bounds on floating-point rounding error (stage 04 on).
//
// IEEE 754 rounds every +, -, *, / and sqrt correctly: the computed result is
// the exact result times (1 + e) with |e| <= u, the unit roundoff (half the
// machine epsilon: 2^-24 in float, 2^-53 in double). A chain of n such
// operations stays within a factor (1 + e)^n, and
//     (1 - u)^n >= 1 - gamma_n,  (1 + u)^n <= 1 + gamma_n,  gamma_n = n u / (1 - n u)
// (Physically Based Rendering, 3rd ed., Pharr, Jakob, Humphreys, sec. 3.9.1,
// eq. 3.8; the bound is Higham's, "Accuracy and Stability of Numerical
// Algorithms", 2nd ed., lemma 3.1). The robust methods of rt (the BVH slab
// test, the triangle distance check, the offset of spawned rays) use these
// bounds instead of an "epsilon" picked by hand.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "config.hpp"

namespace rt {

/// u: the largest relative error of one correctly rounded operation.
constexpr real unit_roundoff = std::numeric_limits<real>::epsilon() / 2;

/// gamma_n = n u / (1 - n u): the relative error bound of n chained operations.
constexpr real gamma_n(int n)
{
    return (real(n) * unit_roundoff) / (1 - real(n) * unit_roundoff);
}

namespace detail {

/// The float or double x moved by |ulps| units in the last place towards +inf
/// for positive ulps (towards -inf for negative ones), by integer arithmetic on
/// its bits. (x must not be zero: offset_ray_origin adds near zero instead, and
/// next_up and next_down treat zero apart.)
template <class Float>
Float add_ulps(Float x, std::int64_t ulps)
{
    using Bits = std::conditional_t<sizeof(Float) == 4, std::int32_t, std::int64_t>;
    Bits bits;
    std::memcpy(&bits, &x, sizeof bits);
    // the bit pattern of a float grows with its magnitude, on either side of zero
    bits = Bits(bits + (x < 0 ? -ulps : ulps));
    Float moved;
    std::memcpy(&moved, &bits, sizeof moved);
    return moved;
}

} // namespace detail

/// The next representable value above x (towards +inf): std::nextafter(x,
/// +inf), bit for bit (-0 and +0 both go to the smallest subnormal, +inf and
/// NaN stay), one step of the bit pattern (PBR 3rd ed., sec. 3.9.4) without
/// std::nextafter's call into the maths library: a spawned ray takes up to six
/// (spawn.hpp).
inline real next_up(real x)
{
    if (std::isnan(x) || x == std::numeric_limits<real>::infinity())
        return x;
    if (x == 0)
        return std::numeric_limits<real>::denorm_min();
    return detail::add_ulps(x, 1);
}

/// The next representable value below x (towards -inf), as std::nextafter(x, -inf).
inline real next_down(real x)
{
    if (std::isnan(x) || x == -std::numeric_limits<real>::infinity())
        return x;
    if (x == 0)
        return -std::numeric_limits<real>::denorm_min();
    return detail::add_ulps(x, -1);
}

} // namespace rt
