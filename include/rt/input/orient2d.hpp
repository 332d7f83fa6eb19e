// orient2d.hpp - which side of the line a b the point c lies on, decided exactly.
//
// Usage:
//     const rt::detail::dvec2 a(0, 0), b(1, 0), c(0.5, 1e-300);
//     rt::detail::orient2d(a, b, c);        // +1: counter-clockwise (c left of a->b)
//     rt::detail::orient2d_naive(a, b, c);  // the plain double determinant, for comparison
//
// orient2d(a, b, c) is the sign of the 2x2 determinant (a - c) x (b - c). In
// double arithmetic its sign is wrong for nearly collinear points, and a
// polygon triangulation that trusts a wrong sign cuts an ear that is not one.
// Here the double result is kept when its error bound proves the sign and the
// rare undecided case is computed exactly with floating-point expansions
// (J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast
// Robust Geometric Predicates", Discrete & Computational Geometry 18(3), 1997:
// sec. 2 for the exact sums and products, sec. 4 for orient2d and its error
// bound). triangulate.hpp makes every decision with it; the tests in
// tests/library_triangulate.cpp show orient2d_naive failing where it holds.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <glm/vec2.hpp>

namespace rt {
namespace detail {

using dvec2 = glm::dvec2; // the projected corners: exact copies of float (or double) coordinates

// ---- exact arithmetic (Shewchuk 1997, sec. 2) --------------------------------
// An expansion is a sum of doubles ordered by increasing magnitude whose
// nonzero components do not overlap (their bits do not share positions);
// its sign is the sign of its largest nonzero component (Shewchuk, sec. 2.2).
// Exact as long as no product underflows or overflows: |coordinates| between
// about 1e-70 and 1e70, which every float and every coordinate the loaders
// accept satisfy.

/// a + b = x + y exactly, |y| <= ulp(x)/2 (Shewchuk, Theorem 7, Knuth's Two-Sum).
inline void two_sum(double a, double b, double& x, double& y)
{
    x = a + b;
    const double b_virtual = x - a;
    const double a_virtual = x - b_virtual;
    const double b_roundoff = b - b_virtual;
    const double a_roundoff = a - a_virtual;
    y = a_roundoff + b_roundoff;
}

/// a * b = x + y exactly (Shewchuk's Two-Product, sec. 2.6; the rounding
/// error of a product is a double, which a fused multiply-add gives exactly).
inline void two_product(double a, double b, double& x, double& y)
{
    x = a * b;
    y = std::fma(a, b, -x);
}

/// e + b (Shewchuk, Grow-Expansion, Theorem 10), zero components dropped.
inline std::vector<double> grow_expansion(const std::vector<double>& e, double b)
{
    std::vector<double> h;
    h.reserve(e.size() + 1);
    double q = b;
    for (const double component : e) {
        double sum = 0, error = 0;
        two_sum(q, component, sum, error);
        if (error != 0)
            h.push_back(error);
        q = sum;
    }
    if (q != 0 || h.empty())
        h.push_back(q);
    return h;
}

/// e + f (Shewchuk, Expansion-Sum, Theorem 12: e grown by each component of f).
inline std::vector<double> expansion_sum(std::vector<double> e, const std::vector<double>& f)
{
    for (const double component : f)
        e = grow_expansion(e, component);
    return e;
}

/// e * b (Shewchuk, Scale-Expansion, Theorem 19), zero components dropped.
inline std::vector<double> scale_expansion(const std::vector<double>& e, double b)
{
    std::vector<double> h;
    if (e.empty())
        return {0.0};
    double q = 0, low = 0;
    two_product(e[0], b, q, low);
    if (low != 0)
        h.push_back(low);
    for (std::size_t i = 1; i < e.size(); ++i) {
        double high = 0, product_low = 0, sum = 0, error = 0;
        two_product(e[i], b, high, product_low);
        two_sum(q, product_low, sum, error);
        if (error != 0)
            h.push_back(error);
        two_sum(high, sum, q, error); // |sum| <= |high| here (Shewchuk's Fast-Two-Sum), Two-Sum is exact anyway
        if (error != 0)
            h.push_back(error);
    }
    if (q != 0 || h.empty())
        h.push_back(q);
    return h;
}

/// e * f: the sum of e scaled by each component of f.
inline std::vector<double> expansion_product(const std::vector<double>& e, const std::vector<double>& f)
{
    std::vector<double> result{0.0};
    for (const double component : f)
        result = expansion_sum(result, scale_expansion(e, component));
    return result;
}

/// -1, 0 or +1: the sign of an expansion (its largest nonzero component's).
inline int expansion_sign(const std::vector<double>& e)
{
    for (std::size_t i = e.size(); i-- > 0;)
        if (e[i] != 0)
            return e[i] > 0 ? 1 : -1;
    return 0;
}

/// a - b as an exact expansion of two components.
inline std::vector<double> exact_difference(double a, double b)
{
    double x = 0, y = 0;
    two_sum(a, -b, x, y);
    return y == 0 ? std::vector<double>{x} : std::vector<double>{y, x};
}

/// The exact sign of (ax - cx)(by - cy) - (ay - cy)(bx - cx).
inline int orient2d_exact(const dvec2& a, const dvec2& b, const dvec2& c)
{
    const std::vector<double> left = expansion_product(exact_difference(a.x, c.x), exact_difference(b.y, c.y));
    std::vector<double> right = expansion_product(exact_difference(a.y, c.y), exact_difference(b.x, c.x));
    for (double& component : right)
        component = -component;
    return expansion_sign(expansion_sum(left, right));
}

/// The same determinant in double arithmetic only: what a plain
/// implementation computes (kept for the tests, which show it failing).
inline int orient2d_naive(const dvec2& a, const dvec2& b, const dvec2& c)
{
    const double det = (a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x);
    return det > 0 ? 1 : det < 0 ? -1 : 0;
}

/// +1 when a, b, c turn counter-clockwise, -1 clockwise, 0 on one line:
/// exactly, for any double coordinates within the range above. The double
/// result is kept when its error bound shows its sign is right: Shewchuk's
/// orient2d filter, |det| >= (3 + 16 eps) eps (|detleft| + |detright|) with
/// eps = 2^-53 (Shewchuk 1997, sec. 4.2, the bound ccwerrboundA); otherwise
/// the exact expansion decides.
inline int orient2d(const dvec2& a, const dvec2& b, const dvec2& c)
{
    const double detleft = (a.x - c.x) * (b.y - c.y);
    const double detright = (a.y - c.y) * (b.x - c.x);
    const double det = detleft - detright;
    const double eps = std::numeric_limits<double>::epsilon() / 2; // 2^-53, the unit roundoff
    const double bound = (3 + 16 * eps) * eps * (std::fabs(detleft) + std::fabs(detright));
    if (det > bound)
        return 1;
    if (-det > bound)
        return -1;
    return orient2d_exact(a, b, c);
}

/// Whether segments (a, b) and (c, d) cross at one point inside both.
inline bool proper_crossing(const dvec2& a, const dvec2& b, const dvec2& c, const dvec2& d)
{
    const int abc = orient2d(a, b, c), abd = orient2d(a, b, d);
    const int cda = orient2d(c, d, a), cdb = orient2d(c, d, b);
    return abc * abd < 0 && cda * cdb < 0;
}

/// Whether p lies strictly between a and b on the segment (a, b).
inline bool inside_segment(const dvec2& p, const dvec2& a, const dvec2& b)
{
    if (p == a || p == b || orient2d(a, b, p) != 0)
        return false;
    // on the line: between when the coordinates (of the axis that varies) are
    if (a.x != b.x)
        return (p.x > std::min(a.x, b.x)) && (p.x < std::max(a.x, b.x));
    return (p.y > std::min(a.y, b.y)) && (p.y < std::max(a.y, b.y));
}

} // namespace detail
} // namespace rt
