// library_sphere_stable.cpp - the library's ray-sphere method, rt::hit_sphere
// (include/rt/intersection/sphere_stable.hpp: the stable method of Ray Tracing Gems ch. 7),
// against the textbook quadratic.
//
// The contract every ray-sphere function keeps (tests/sphere_contract.hpp,
// the checks stage 03 runs on the student's quadratic), on rt::hit_sphere.
//
// The accuracy table (tests/sphere_accuracy.hpp): a unit sphere at distances 1e1 ... 1e6 and a large
// "ground" sphere seen from just above it, each root compared with the exact
// root (a closed form, or the same quadratic evaluated in long double from the
// same float inputs, whose error is far below one ulp of real). The stable
// method stays within 4 ulps everywhere; the textbook's error passes that
// bound, and in float, far away, it misses rays that hit and hits rays that
// miss. The table is printed (doctest MESSAGE); docs/stages/03-going-further.md
// quotes it, checked by tests/docs_figures.cpp from the same code.
//
// The textbook method measured here is the stage-03 exercise itself,
// rt::hit_sphere_textbook, whose reference body is the textbook formula. Its
// failures are asserted in the reference only; in a student kit those cases
// say SKIPPED, with the reason (tests/textbook_methods.hpp): not written yet,
// or the student's own method, which is printed and never marked down.
#include "rt_doctest.hpp"
#include "sphere_accuracy.hpp"
#include "sphere_contract.hpp"
#include "textbook_methods.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include <rt/core/hit_record.hpp>
#include <rt/core/ray.hpp>
#include <rt/intersection/sphere.hpp>
#include <rt/intersection/sphere_stable.hpp>

namespace {

using rt::real;
using rt_test::both_methods;
using rt_test::distance_row;
using rt_test::fan_size;
using rt_test::ground_row;
using rt_test::infinity;
using rt_test::outcome;
using rt_test::real_is_float;
using rt_test::reference_is_exact;
using rt_test::ulp_bound;
using wide = rt_test::wide;

} // namespace

TEST_CASE("stable method, contract: closed-form hits at distance 5, t = 4 / |d|")
{
    rt_test::check_closed_form_hits(rt_test::stable);
}

TEST_CASE("stable method, contract: a ray starting inside hits the far side, back face, normal facing the ray")
{
    rt_test::check_ray_from_inside(rt_test::stable);
}

TEST_CASE("stable method, contract: a tangent ray touches at one point, just outside it misses")
{
    rt_test::check_tangent_ray(rt_test::stable);
}

TEST_CASE("stable method, contract: rays pointing away miss, roots behind are found only when tmin allows")
{
    rt_test::check_rays_pointing_away(rt_test::stable);
}

TEST_CASE("stable method, contract: the closed interval tmin, tmax around the roots 4 and 6")
{
    rt_test::check_interval(rt_test::stable);
}

TEST_CASE("stable method, contract: random rays at near spheres, point on the sphere within 6 ulps, unit normal within 2")
{
    // p = o + t d carries the error of t (<= 4 ulps) plus two roundings; the
    // normal is normalised.
    int hits = 0;
    const rt_test::near_bounds worst = rt_test::check_random_rays_at_near_spheres(rt_test::stable, {6, 2}, hits);
    MESSAGE("worst in ulps: point off the sphere " << worst.on_sphere << ", normal length off 1 " << worst.unit_normal
                                                   << " (" << hits << " hits)");
}

TEST_CASE("stable method, contract: material copied, barycentrics and primitive zero, a miss leaves the record untouched")
{
    rt_test::check_record_fields(rt_test::stable);
}

TEST_CASE("stable method, contract: a degenerate ray (d = 0) misses")
{
    rt_test::check_degenerate_ray(rt_test::stable);
}

TEST_CASE("stable method, contract: near spheres, random rays, t within 4 ulps of the exact root")
{
    if (!reference_is_exact) {
        RT_SKIP("long double has too few bits to be the exact reference for this rt::real");
    }
    rt_test::check_against_exact_roots(rt_test::stable, ulp_bound);
}

TEST_CASE("accuracy table: a unit sphere at 1e1..1e6 and a ground sphere, textbook vs stable (printed)")
{
    if (!reference_is_exact) {
        RT_SKIP("long double has too few bits to be the exact reference for this rt::real: no table");
    }
    MESSAGE(rt_test::accuracy_tables());
}

TEST_CASE("stable method: t within 4 ulps of the exact root at every distance 1e1..1e6 (centred, off-centre, grazing, oblique)")
{
    if (!reference_is_exact) {
        RT_SKIP("long double has too few bits to be the exact reference for this rt::real");
    }
    for (const distance_row& row : rt_test::distance_table()) {
        CAPTURE(double(row.D));
        for (const outcome* o : {&row.centred[1], &row.off_centre[1], &row.grazing[1]}) {
            CHECK(o->hit);
            CHECK(o->ulps <= ulp_bound);
        }
        CHECK(row.fan[1].rays == fan_size); // the reference says every fan ray hits
        CHECK(row.fan[1].misses == 0);
        CHECK(row.fan[1].worst_ulps <= ulp_bound);
        CHECK(row.miss_fan[1].rays == fan_size); // and every ray of the other fan misses
        CHECK(row.miss_fan[1].false_hits == 0);
    }
}

TEST_CASE("stable method: t within 4 ulps for a ground sphere of radius 1e2..1e5 seen from just above it, with the chapter's c in float it is not")
{
    if (!reference_is_exact) {
        RT_SKIP("long double has too few bits to be the exact reference for this rt::real");
    }
    for (const ground_row& row : rt_test::ground_table()) {
        CAPTURE(double(row.R));
        CAPTURE(double(row.h));
        CHECK(row.result[1].hit);
        CHECK(row.result[1].ulps <= ulp_bound);
        // c = |f|^2 - R^2 = h (2R + h) is the difference of two reals near R^2:
        // rounded in float its error is about R^2 2^-24, against a value of
        // about 2 R h. That passes the bound from R ~ 1e4 (in double, where the
        // products of these few-bit inputs are exact, it does not show).
        if (real_is_float && row.R >= real(1e4))
            CHECK(row.chapter.ulps > ulp_bound);
    }
}

TEST_CASE("textbook quadratic: its error passes 4 ulps from distance 1e2 on, in float from 1e4 on it misses hits and hits misses")
{
    if (!reference_is_exact) {
        RT_SKIP("long double has too few bits to be the exact reference for this rt::real");
    }
    // The discriminant is the difference of two products of size D^2 |d|^2,
    // each rounded with relative error eps (2^-24 in float, 2^-53 in double),
    // while the true value is (R^2 - h^2)|d|^2 <= 1: its absolute error grows
    // like D^2 eps. Near (D = 10) rays well inside the silhouette are still
    // accurate; by D = 100 the error is past the bound; in float D^2 eps
    // passes 1 at D ~ 4e3, after which the discriminant is noise: negative for
    // some rays that hit (a miss), positive for some that pass (a false hit),
    // and the depth of the others off by about R. D = 1e3 is the edge of that
    // (D^2 eps ~ 0.06 against a margin of 0.19 or 0.21): reported, not asserted.
    if (const std::string why = rt_test::textbook_skip_reason(rt_test::textbook_not_done(), "hit_sphere_textbook (stage 03)");
        !why.empty())
        RT_SKIP(why); // (the accuracy table's case prints what it does)
    const std::vector<distance_row> rows = rt_test::distance_table();
    REQUIRE(rows.front().D == real(10));
    CHECK(rows.front().centred[0].ulps <= ulp_bound);
    CHECK(rows.front().off_centre[0].ulps <= ulp_bound);
    for (const distance_row& row : rows) {
        CAPTURE(double(row.D));
        const double worst = std::max({row.centred[0].ulps, row.off_centre[0].ulps, row.grazing[0].ulps, row.fan[0].worst_ulps});
        if (row.D >= real(100))
            CHECK(worst > ulp_bound);
        if (real_is_float && row.D >= real(1e4)) {
            CHECK(row.fan[0].misses > 0);
            CHECK(row.miss_fan[0].false_hits > 0);
            CHECK(row.centred[0].depth_error >= wide(0.5)); // the sphere looks flat: hit at its centre's depth
        } else if (!real_is_float || row.D <= real(100)) {
            // in double D^2 eps is 1e-4 at 1e6: hit or miss is still right, the depth is not
            CHECK(row.fan[0].misses == 0);
            CHECK(row.miss_fan[0].false_hits == 0);
        }
    }
    // Near the surface of a large sphere, c = |f|^2 - R^2 cancels as well.
    for (const ground_row& row : rt_test::ground_table()) {
        CAPTURE(double(row.R));
        CAPTURE(double(row.h));
        CHECK(row.result[0].ulps > ulp_bound);
    }
}

TEST_CASE("sphere_roots_stable: ordered roots t0 <= t1 on the whole line, negative behind the origin")
{
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    real t0 = 0, t1 = 0;
    REQUIRE(rt::sphere_roots_stable(s, rt::ray{rt::vec3(0), rt::vec3(0, 0, -1)}, t0, t1));
    CHECK(t0 == real(4));
    CHECK(t1 == real(6));
    REQUIRE(rt::sphere_roots_stable(s, rt::ray{rt::vec3(0), rt::vec3(0, 0, 1)}, t0, t1));
    CHECK(t0 == real(-6));
    CHECK(t1 == real(-4));
    REQUIRE(rt::sphere_roots_stable(s, rt::ray{rt::vec3(0, 0, -5), rt::vec3(2, 0, 0)}, t0, t1)); // from the centre
    CHECK(t0 == real(-0.5));
    CHECK(t1 == real(0.5));
    // the origin on the sphere, the ray tangent there: one double root at 0
    REQUIRE(rt::sphere_roots_stable(s, rt::ray{rt::vec3(1, 0, -5), rt::vec3(0, 1, 0)}, t0, t1));
    CHECK(t0 == 0);
    CHECK(t1 == 0);
    CHECK_FALSE(rt::sphere_roots_stable(s, rt::ray{rt::vec3(0, 2, 0), rt::vec3(0, 0, -1)}, t0, t1));
}

TEST_CASE("one ulp outside a sphere's silhouette the stable method misses, and a tangent ray is one double root")
{
    // The stable method sees h^2 = 1 + 2 ulp > R^2 and misses.
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    const rt::ray one_ulp_out{rt::vec3(std::nextafter(real(1), infinity), 0, 0), rt::vec3(0, 0, -1)};
    rt::hit_record rec;
    CHECK_FALSE_MESSAGE(rt::hit_sphere(s, one_ulp_out, 0, infinity, rec), "expected the stable method to miss");
    real t0 = 0, t1 = 0;
    REQUIRE(rt::sphere_roots_stable(s, rt::ray{rt::vec3(1, 0, 0), rt::vec3(0, 0, -1)}, t0, t1));
    CHECK(t0 == t1);
}

TEST_CASE("one ulp outside a sphere's silhouette the textbook formula still hits")
{
    // In the textbook's discriminant 25 - ((h^2 + 25) - 1) the 2 ulp of h^2 =
    // 1 + 2 ulp vanish next to 25, so it still reports the tangent hit (the
    // stage-03 exercise, rt::hit_sphere_textbook: asserted in the reference only).
    rt::sphere s;
    s.center = rt::vec3(0, 0, -5);
    const rt::ray one_ulp_out{rt::vec3(std::nextafter(real(1), infinity), 0, 0), rt::vec3(0, 0, -1)};
    rt::hit_record rec;
    const std::string not_done =
        rt_test::not_done_message([&] { rt::hit_sphere_textbook(s, one_ulp_out, 0, infinity, rec); });
    if (const std::string why = rt_test::textbook_skip_reason(not_done, "hit_sphere_textbook (stage 03)"); !why.empty()) {
        if (not_done.empty())
            MESSAGE("your hit_sphere_textbook " << (rt::hit_sphere_textbook(s, one_ulp_out, 0, infinity, rec) ? "hits"
                                                                                                              : "misses")
                                                << " the ray one ulp outside the silhouette");
        RT_SKIP(why);
    }
    CHECK_MESSAGE(rt::hit_sphere_textbook(s, one_ulp_out, 0, infinity, rec),
                  "expected the textbook formula's tangent hit");
}
