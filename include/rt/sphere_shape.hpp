// sphere_shape.hpp - the sphere a scene holds: centre c, radius R, material.
//
// Only the data: the intersection lives apart (sphere.hpp, the stage-03
// exercise; sphere_stable.hpp, the library's method), so that the scene, its
// loader and the BVH never include an exercise and an edit to one rebuilds
// only what uses it.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include "rounding.hpp"
#include "vec.hpp"

namespace rt {

struct sphere {
    vec3 center{0};     ///< c
    real radius = 1;    ///< R
    int material = -1;  ///< index into scene::materials; -1: the default material
};

/// The smallest radius rt represents for a sphere centred at c: 16 u max|c_k|
/// (u the unit roundoff), that is, about 8 units in the last place of the
/// centre's largest coordinate. The coordinates of points near c are spaced
/// that coarsely, so a smaller sphere's hit points round onto a handful of
/// grid points around its centre, or onto the centre itself: a radius of
/// 7.1e-4 at a centre near 4e5 (a float ulp there is 0.031) gave hit points
/// equal to the centre and a (nan, nan, nan) normal (issue 19). The scene
/// loader refuses such spheres (sphere_fits_its_position); hit_sphere still
/// returns a unit normal for them.
inline real smallest_sphere_radius(const vec3& c)
{
    const real largest = std::fmax(std::fabs(c.x), std::fmax(std::fabs(c.y), std::fabs(c.z)));
    return 16 * unit_roundoff * largest;
}

/// Whether rt can represent the sphere at its position: a radius of at least
/// smallest_sphere_radius(center), and finite.
inline bool sphere_fits_its_position(const sphere& s)
{
    return std::isfinite(s.radius) && s.radius >= smallest_sphere_radius(s.center) && s.radius > 0;
}

namespace detail {

inline std::string short_number(double x)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", x);
    return text;
}

} // namespace detail

/// The parts of the loader's one-line message for a sphere that does not fit
/// its position: what was expected, what was found, and the hint.
inline std::string sphere_radius_expected(const sphere& s)
{
    return "a radius of at least " + detail::short_number(double(smallest_sphere_radius(s.center))) +
           " for a sphere centred at (" + detail::short_number(double(s.center.x)) + ", " +
           detail::short_number(double(s.center.y)) + ", " + detail::short_number(double(s.center.z)) +
           ") (8 units in the last place of its largest coordinate)";
}

inline std::string sphere_radius_found(const sphere& s)
{
    return "radius " + detail::short_number(double(s.radius));
}

constexpr const char* sphere_scale_hint =
    "the sphere is smaller than the rounding of its centre; move the scene nearer the origin, enlarge the "
    "sphere, or build with -DRT_USE_DOUBLE=ON";

} // namespace rt
