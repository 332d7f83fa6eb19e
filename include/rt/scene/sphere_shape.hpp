// sphere_shape.hpp - the sphere a scene holds: centre c, radius R, material.
//
// Only the data: the intersection lives apart (sphere.hpp, the stage-03
// exercise; sphere_stable.hpp, the library's method), so that the scene, its
// loader and the BVH never include an exercise and an edit to one rebuilds
// only what uses it.
#pragma once

#include <cmath>
#include <string>

#include "../core/error.hpp"
#include "../core/hit_record.hpp"
#include "../core/ray.hpp"
#include "../core/rounding.hpp"
#include "../core/vec.hpp"

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

/// Given (not an exercise): fills a sphere's hit record for the root t that an
/// intersection found (FCG 4th ed., sec. 4.4.1): rec.t = t, rec.point = p + t d,
/// the outward unit normal normalize(point - c) (unit length even where the
/// computed point is an ulp off the surface; -d/|d| when the point rounds onto
/// the centre), front_face = d . outward <= 0 (a tangent ray counts as hitting
/// the outside), geometric_normal = normal = the outward normal turned to face
/// the ray, the sphere's material, primitive = b1 = b2 = 0. rec.shape is left
/// alone (the caller knows which shape it asked about). Both the stage-03
/// exercise (sphere.hpp) and the library's hit_sphere (sphere_stable.hpp) call
/// it once they have chosen their root.
inline void fill_sphere_record(const sphere& s, const ray& r, real t, hit_record& rec)
{
    rec.t = t;
    rec.point = r.at(t);
    const vec3 local = rec.point - s.center;
    const real length2 = glm::dot(local, local);
    const vec3 outward = length2 > 0 && std::isfinite(length2) ? glm::normalize(local) : -glm::normalize(r.direction);
    rec.front_face = glm::dot(r.direction, outward) <= 0;
    rec.geometric_normal = rec.front_face ? outward : -outward;
    rec.normal = rec.geometric_normal;
    rec.material = s.material;
    rec.primitive = 0;
    rec.b1 = rec.b2 = 0;
}

namespace detail {

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

} // namespace detail

} // namespace rt
