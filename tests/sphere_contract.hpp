// sphere_contract.hpp - the contract of a ray-sphere intersection function,
// as doctest checks written once: tests/stage03_sphere.cpp runs them on the
// student's hit_sphere_textbook, tests/library_sphere_stable.cpp on the
// library's hit_sphere.
//
// Every check is a property a correct answer has (closed-form roots, the
// closed interval [tmin, tmax], the hit point on the sphere, the record left
// untouched on a miss), never a value one method happens to give: a function
// more accurate than the textbook's always passes. Each check says in words
// what was expected, and within a function the checks are ordered so that the
// first failure names the cause (hit or miss, then which root, then accuracy).
#pragma once

#include "rt_doctest.hpp"
#include "sphere_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>

#include <rt/core/hit_record.hpp>
#include <rt/core/ray.hpp>
#include <rt/scene/sphere_shape.hpp>
#include <rt/core/vec.hpp>

namespace rt_test {

inline real next_up(real x) { return std::nextafter(x, infinity); }
inline real next_down(real x) { return std::nextafter(x, -infinity); }

/// A unit sphere at distance 5 along -z, rays from the origin: t = 4 / |d|
/// (FCG sec. 4.4.1: the roots of the quadratic are 4 and 6 for |d| = 1).
inline void check_closed_form_hits(const method& m)
{
    const std::string method_name = m.name; // a std::string: doctest prints a char* as a pointer
    CAPTURE(method_name);
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    for (real scale : {real(1), real(2), real(0.5)}) {
        CAPTURE(double(scale));
        const rt::ray r{rt::vec3(0), rt::vec3(0, 0, -scale)};
        rt::hit_record rec;
        INFO("the ray from the origin along -z with |d| = " << double(scale) << " meets the sphere at t = "
             << 4 / double(scale) << " (entering) and t = " << 6 / double(scale) << " (leaving)");
        REQUIRE_MESSAGE(m.hit(s, r, 0, infinity, rec), "expected a hit: the ray points at the sphere's centre");
        const real nearer = real(4) / scale, farther = real(6) / scale; // every step is exact for these inputs
        // a std::string: doctest prints a char* in INFO as a pointer
        const std::string diagnosis = rec.t == farther ? "found the far root: return the smaller root first, the larger "
                                                   "only when the smaller is outside [tmin, tmax]"
                                : (scale != 1 && (rec.t == 4 || rec.t == 6))
                                    ? "found a distance, not a multiple of d: t counts lengths of d, do not normalise d"
                                    : "found neither root";
        INFO("expected the nearer root t = " << double(nearer) << ", found t = " << double(rec.t) << ": "
                                             << (rec.t == nearer ? std::string("right") : diagnosis));
        REQUIRE(rec.t == nearer);
        CHECK(rec.point == rt::vec3(0, 0, -4));
        CHECK(rec.normal == rt::vec3(0, 0, 1));
        CHECK(rec.geometric_normal == rt::vec3(0, 0, 1));
        CHECK_MESSAGE(rec.front_face, "expected front_face = true: the origin is outside, and the ray enters the "
                                      "sphere at t = "
                                          << double(nearer) << "; found the back face");
    }
    // passing 0.6 R from the centre: t = 5 - sqrt(1 - 0.36) = 4.2, normal (0.6, 0, 0.8)
    const rt::ray off{rt::vec3(real(0.6), 0, 0), rt::vec3(0, 0, -1)};
    rt::hit_record rec;
    REQUIRE_MESSAGE(m.hit(s, off, 0, infinity, rec), "expected a hit: the ray passes 0.6 R from the centre");
    const wide exact = 5 - std::sqrt(1 - wide(real(0.6)) * wide(real(0.6)));
    // the nearer root first, so that a far root is named as such before any accuracy check
    CHECK_MESSAGE(rec.t < real(5), "expected the nearer root t = 4.2, not the far one t = 5.8");
    INFO("t = " << double(rec.t) << " against the exact 4.2000000...: expected within 4 ulps");
    CHECK(error_ulps(rec.t, exact) <= ulp_bound);
    CHECK(rec.normal.x == doctest::Approx(0.6).epsilon(1e-6));
    CHECK(rec.normal.z == doctest::Approx(0.8).epsilon(1e-6));
}

/// A ray starting inside has one root ahead: the far side, seen from inside.
inline void check_ray_from_inside(const method& m)
{
    portable_random random(3);
    const std::string method_name = m.name;
    CAPTURE(method_name);
    // from the centre: t = R / |d| exactly in the quadratic's terms
    rt::sphere s;
    s.center = rt::vec3(1, 2, 3);
    s.radius = 2;
    const rt::ray from_centre{s.center, rt::vec3(0, real(0.5), 0)};
    rt::hit_record rec;
    REQUIRE_MESSAGE(m.hit(s, from_centre, 0, infinity, rec),
                    "expected a hit: a ray from the centre leaves the sphere (the larger root, t = R / |d| = 4)");
    CHECK_MESSAGE(rec.t == real(4), "expected t = R / |d| = 4: the smaller root (-4) is behind the origin");
    CHECK(rec.point == rt::vec3(1, 4, 3));
    CHECK_FALSE_MESSAGE(rec.front_face, "expected front_face = false: the ray starts inside and leaves through the back face");
    CHECK_MESSAGE(rec.normal == rt::vec3(0, -1, 0), "expected the inward normal: it faces the ray");
    // from random points inside, in random directions
    for (int k = 0; k < 200; ++k) {
        const rt::vec3 towards = random.unit_vector();
        const real depth = random.uniform();
        const rt::vec3 origin = s.center + towards * (s.radius * real(0.95) * depth);
        const rt::vec3 direction = random.unit_vector();
        const real length = random.between(real(0.5), real(2));
        const rt::ray r{origin, direction * length};
        CAPTURE(k);
        CAPTURE(r);
        REQUIRE_MESSAGE(m.hit(s, r, 0, infinity, rec), "expected a hit: every ray from inside leaves the sphere");
        REQUIRE_MESSAGE(rec.t > 0, "expected the root ahead of the origin (t > 0)");
        REQUIRE_FALSE_MESSAGE(rec.front_face, "expected front_face = false: the ray starts inside the sphere");
        REQUIRE_MESSAGE(glm::dot(rec.normal, r.direction) < 0, "expected the normal to face the ray");
        REQUIRE_MESSAGE(glm::dot(rec.normal, rec.point - s.center) < 0, "expected the inward normal");
        // and it is the only root ahead: nothing further along the ray
        rt::hit_record beyond;
        REQUIRE_FALSE_MESSAGE(m.hit(s, r, rec.t * real(1.001), infinity, beyond),
                            "expected no second hit beyond t = " << double(rec.t) << ": a ray from inside has one root ahead");
    }
}

/// A tangent ray: one double root, a hit on the outside.
inline void check_tangent_ray(const method& m)
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    const std::string method_name = m.name;
    CAPTURE(method_name);
    const rt::ray tangent{rt::vec3(1, 0, 0), rt::vec3(0, 0, -1)};
    rt::hit_record rec;
    REQUIRE_MESSAGE(m.hit(s, tangent, 0, infinity, rec), "expected a hit: a tangent ray touches the sphere (discriminant 0)");
    CHECK_MESSAGE(rec.t == real(5), "expected the double root t = 5");
    CHECK(rec.point == rt::vec3(1, 0, -5));
    CHECK(rec.normal == rt::vec3(1, 0, 0));
    CHECK_MESSAGE(glm::dot(rec.normal, tangent.direction) == 0, "expected the normal perpendicular to a tangent ray");
    CHECK_MESSAGE(rec.front_face, "expected front_face = true: a tangent ray counts as hitting the outside");
    const rt::ray outside{rt::vec3(1 + real(1) / 1024, 0, 0), rt::vec3(0, 0, -1)};
    CHECK_FALSE_MESSAGE(m.hit(s, outside, 0, infinity, rec),
                        "expected a miss: the ray passes 1/1024 outside the sphere's silhouette");
}

/// Roots behind the origin count only when tmin lets them.
inline void check_rays_pointing_away(const method& m)
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    const std::string method_name = m.name;
    CAPTURE(method_name);
    const rt::ray away{rt::vec3(0), rt::vec3(0, 0, 1)}; // roots at -6 and -4
    rt::hit_record rec;
    CHECK_FALSE_MESSAGE(m.hit(s, away, 0, infinity, rec), "expected a miss: both roots (-6, -4) are behind the origin, tmin = 0");
    REQUIRE_MESSAGE(m.hit(s, away, -100, infinity, rec), "expected a hit: tmin = -100 lets in the roots -6 and -4");
    CHECK_MESSAGE(rec.t == real(-6), "expected the nearer root in [tmin, tmax], t = -6");
    CHECK_MESSAGE(rec.front_face, "expected front_face = true: the line enters the sphere at t = -6");
    const rt::ray beside{rt::vec3(0, 3, 0), rt::vec3(0, 0, -1)}; // passes 3 R from the centre
    CHECK_FALSE_MESSAGE(m.hit(s, beside, -100, infinity, rec), "expected a miss: the line passes 3 R from the centre");
}

/// The closed interval [tmin, tmax] around the roots 4 and 6.
inline void check_interval(const method& m)
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    const rt::ray r{rt::vec3(0), rt::vec3(0, 0, -1)};
    struct interval_case {
        real tmin, tmax;
        bool hit;
        real t;
    };
    const interval_case cases[] = {
        {0, infinity, true, 4},
        {0, 4, true, 4},                      // the interval is closed
        {0, next_down(4), false, 0},          // the hit just beyond tmax is rejected
        {4, 4, true, 4},
        {next_up(4), infinity, true, 6},      // the first root below tmin: the second is returned
        {next_up(4), 6, true, 6},
        {next_up(4), next_down(6), false, 0}, // between the roots
        {real(4.5), real(5.5), false, 0},
        {next_up(6), infinity, false, 0},     // both roots below tmin
        {-infinity, infinity, true, 4},
    };
    const std::string method_name = m.name;
    CAPTURE(method_name);
    for (const interval_case& k : cases) {
        CAPTURE(double(k.tmin));
        CAPTURE(double(k.tmax));
        rt::hit_record rec;
        INFO("roots t = 4 and t = 6: expected " << (k.hit ? "a hit at t = " + std::to_string(int(k.t)) : std::string("a miss"))
             << " for tmin <= t <= tmax (both ends included)");
        REQUIRE(m.hit(s, r, k.tmin, k.tmax, rec) == k.hit);
        if (k.hit)
            CHECK(rec.t == k.t);
    }
}

/// Worst errors in ulps, for random_rays_at_near_spheres.
struct near_bounds {
    double on_sphere, unit_normal;
};

/// Random rays at spheres 1.5 to 10 radii away: the hit point on the sphere
/// within `bound.on_sphere` ulps of the largest magnitude involved, the normal
/// unit within `bound.unit_normal` ulps of 1 and facing the ray. Returns the
/// worst errors seen and counts the hits.
inline near_bounds check_random_rays_at_near_spheres(const method& m, const near_bounds& bound, int& hits)
{
    portable_random random(11);
    near_bounds worst{0, 0};
    hits = 0;
    const std::string method_name = m.name;
    CAPTURE(method_name);
    auto largest = [](const rt::vec3& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); };
    for (int k = 0; k < 2000; ++k) {
        rt::sphere s;
        s.center = random.in_box(5);
        s.radius = random.between(real(0.25), 3);
        s.material = k % 5;
        const rt::vec3 from = random.unit_vector();
        const real away = random.between(real(1.5), 10);
        const rt::vec3 origin = s.center + from * (s.radius * away);
        const rt::vec3 towards = random.unit_vector();
        const real reach = random.between(0, real(1.2));
        const rt::vec3 aim = s.center + towards * (s.radius * reach);
        const real length = random.between(real(0.1), 4);
        const rt::ray r{origin, (aim - origin) * length};
        CAPTURE(k);
        rt::hit_record rec;
        if (!m.hit(s, r, 0, infinity, rec))
            continue;
        ++hits;
        REQUIRE_MESSAGE(rec.t > 0, "expected a root ahead of the origin: every origin is outside the sphere");
        REQUIRE_MESSAGE(rec.front_face, "expected front_face = true: every origin is outside the sphere, so the nearer "
                                        "root is where the ray enters (a back face means the far root)");
        REQUIRE_MESSAGE(glm::dot(rec.normal, r.direction) <= 0, "expected the normal to face the ray");
        REQUIRE_MESSAGE(glm::dot(rec.normal, rec.point - s.center) > 0, "expected the outward normal");
        REQUIRE_MESSAGE(rec.geometric_normal == rec.normal, "expected geometric_normal == normal: a sphere has no separate shading normal");
        REQUIRE_MESSAGE(rec.material == s.material, "expected the sphere's material index in the record");
        const real scale = std::max({largest(r.origin), largest(rec.point), largest(s.center), s.radius});
        const wide distance = std::sqrt(std::pow(wide(rec.point.x) - s.center.x, 2) + std::pow(wide(rec.point.y) - s.center.y, 2) +
                                        std::pow(wide(rec.point.z) - s.center.z, 2));
        const double off_sphere = double(std::fabs(distance - s.radius) / ulp_at(scale));
        REQUIRE_MESSAGE(off_sphere <= bound.on_sphere, "expected the hit point on the sphere within " << bound.on_sphere
                                                                                                   << " ulps");
        const wide normal_length = std::sqrt(wide(rec.normal.x) * rec.normal.x + wide(rec.normal.y) * rec.normal.y +
                                             wide(rec.normal.z) * rec.normal.z);
        const double off_unit = double(std::fabs(normal_length - 1) / ulp_at(1));
        REQUIRE_MESSAGE(off_unit <= bound.unit_normal, "expected a unit normal, within " << bound.unit_normal << " ulps of 1");
        worst.on_sphere = std::max(worst.on_sphere, off_sphere);
        worst.unit_normal = std::max(worst.unit_normal, off_unit);
    }
    CHECK_MESSAGE(hits > 1500, "expected most of the 2000 rays (aimed within 1.2 R of the centre) to hit, found " << hits);
    return worst;
}

/// What a hit fills and what a miss leaves alone.
inline void check_record_fields(const method& m)
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    const std::string method_name = m.name;
    CAPTURE(method_name);
    for (int material : {7, 0, -1}) {
        s.material = material;
        rt::hit_record rec;
        rec.primitive = 99;
        rec.b1 = rec.b2 = real(0.5);
        REQUIRE_MESSAGE(m.hit(s, rt::ray{rt::vec3(0), rt::vec3(0, 0, -1)}, 0, infinity, rec),
                        "expected a hit: the ray points at the sphere's centre");
        CHECK_MESSAGE(rec.material == material, "expected the sphere's material index copied into the record");
        CHECK_MESSAGE(rec.primitive == 0, "expected primitive = 0 on a sphere");
        CHECK_MESSAGE(rec.b1 == 0, "expected barycentric b1 = 0 on a sphere");
        CHECK_MESSAGE(rec.b2 == 0, "expected barycentric b2 = 0 on a sphere");
    }
    rt::hit_record sentinel;
    sentinel.t = 123;
    sentinel.point = rt::vec3(1, 2, 3);
    sentinel.normal = sentinel.geometric_normal = rt::vec3(0, 1, 0);
    sentinel.front_face = false;
    sentinel.material = 42;
    sentinel.shape = 17;
    sentinel.primitive = 5;
    sentinel.b1 = real(0.25);
    sentinel.b2 = real(0.5);
    rt::hit_record rec = sentinel;
    CHECK_FALSE_MESSAGE(m.hit(s, rt::ray{rt::vec3(0, 3, 0), rt::vec3(0, 0, -1)}, 0, infinity, rec),
                        "expected a miss: the line passes 3 R from the centre");
    CHECK_FALSE_MESSAGE(m.hit(s, rt::ray{rt::vec3(0), rt::vec3(0, 0, -1)}, 0, 1, rec),
                        "expected a miss: the roots 4 and 6 are beyond tmax = 1");
    INFO("expected the record untouched after a miss (the closest-hit loop keeps its best hit in it): it was "
         << rt_doctest::text(sentinel) << ", it is " << rt_doctest::text(rec));
    CHECK(rec.t == sentinel.t);
    CHECK(rec.point == sentinel.point);
    CHECK(rec.normal == sentinel.normal);
    CHECK(rec.geometric_normal == sentinel.geometric_normal);
    CHECK(rec.front_face == sentinel.front_face);
    CHECK(rec.material == sentinel.material);
    CHECK(rec.shape == sentinel.shape);
    CHECK(rec.primitive == sentinel.primitive);
    CHECK(rec.b1 == sentinel.b1);
    CHECK(rec.b2 == sentinel.b2);
}

/// d = 0 is no ray: it misses (the interval test must reject t = 0/0).
inline void check_degenerate_ray(const method& m)
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    const std::string method_name = m.name;
    CAPTURE(method_name);
    for (const rt::vec3& origin : {rt::vec3(0), rt::vec3(0, 0, -5), rt::vec3(0, 0, -4)}) {
        CAPTURE(origin);
        rt::hit_record rec;
        CHECK_FALSE_MESSAGE(m.hit(s, rt::ray{origin, rt::vec3(0)}, 0, infinity, rec),
                            "expected a miss for a ray whose direction is (0, 0, 0): its t is 0/0, a NaN, and "
                            "!(tmin <= t && t <= tmax) rejects it");
    }
}

/// Random rays at near spheres (2 to 10 radii away), aimed within 0.9 R of
/// the centre (hits) or 1.1 R to 2 R (misses, clear of the silhouette): the
/// hit or miss as the exact root says, and t within `ulps` of it.
inline void check_against_exact_roots(const method& m, double ulps)
{
    portable_random random(2024);
    int hits = 0, misses = 0;
    const std::string method_name = m.name;
    CAPTURE(method_name);
    for (int k = 0; k < 3000; ++k) {
        rt::sphere s;
        s.center = random.in_box(3);
        s.radius = random.between(real(0.5), 2);
        const rt::vec3 u = random.unit_vector();
        rt::vec3 w, v;
        perpendiculars(u, w, v);
        const bool aim_inside = k % 3 != 0;
        const real reach = aim_inside ? real(0.9) * std::sqrt(random.uniform()) : random.between(real(1.1), 2);
        const real phi = real(6.283185307179586) * random.uniform();
        const rt::vec3 offset = reach * s.radius * (std::cos(phi) * w + std::sin(phi) * v);
        const real distance = s.radius * random.between(2, 10);
        const real length = random.between(real(0.25), 4);
        const rt::ray r{s.center - u * distance + offset, u * length};
        CAPTURE(k);
        CAPTURE(r);
        wide exact = 0;
        const bool exact_hit = reference_root(s, r, exact);
        REQUIRE(exact_hit == aim_inside); // the reference itself: these rays are far from the silhouette
        rt::hit_record rec;
        const bool hit = m.hit(s, r, 0, infinity, rec);
        INFO("the ray passes " << double(reach) << " R from the centre: expected " << std::string(aim_inside ? "a hit" : "a miss"));
        REQUIRE(hit == aim_inside);
        if (!aim_inside) {
            ++misses;
            continue;
        }
        ++hits;
        REQUIRE_MESSAGE(rec.front_face, "expected front_face = true: the origin is outside, so the nearer root is where "
                                        "the ray enters (a back face means the far root)");
        INFO("expected the nearer root t = " << double(exact) << " (exact, in long double) within " << ulps
                                             << " ulps, found t = " << double(rec.t));
        REQUIRE(error_ulps(rec.t, exact) <= ulps);
    }
    CHECK(hits == 2000);
    CHECK(misses == 1000);
}

} // namespace rt_test
