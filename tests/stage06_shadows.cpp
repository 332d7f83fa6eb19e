// Stage 06 - shadows: a shadow ray to each light, any hit before the light
// (Fundamentals of Computer Graphics, 4th ed., sec. 4.7), started off the
// surface past the hit point's rounding error (spawn_ray_to, PBR 3rd ed.,
// sec. 3.9.5).
//
// The scenes: a sphere above a plane, with a point light on the plane's normal
// through the sphere's centre, so that the shadow is an analytic disc
// (tests/shadow_acne.hpp, shared with docs_figures, which checks the acne
// table of docs/stages/06-shadows.md). Scenes and rays are built here; the
// intersection is the library's (unmarked) accelerator.
#include "rt_doctest.hpp"
#include "shadow_acne.hpp"

#include <cstdio>
#include <string>

#include <rt/bvh/accelerator.hpp>
#include <rt/scene/light.hpp>
#include <rt/scene/light_sample.hpp>
#include <rt/scene/scene.hpp>
#include <rt/shading/shadows.hpp>

namespace {

using rt_test::count_shadow_errors;
using rt_test::fixed_epsilon_visible;
using rt_test::robust_visible;
using rt_test::shadow_count;
using rt_test::shadow_scene;

} // namespace

TEST_CASE("a sphere over a plane: inside the analytic shadow disc is shadowed, outside is lit")
{
    const shadow_scene q = rt_test::make_shadow_scene(1, rt::vec3(0));
    const shadow_count c = count_shadow_errors(q, robust_visible);
    INFO("a 73 x 73 grid of points on the plane, " << c.lit_points << " outside the shadow disc of radius "
         << q.shadow_radius << " (plus one grid step), " << c.shadow_points << " inside it");
    REQUIRE_MESSAGE(c.lit_points > 3000, "expected more than 3000 plane points outside the shadow (the scene's geometry)");
    CHECK_MESSAGE(c.acne == 0, "expected every point outside the shadow to see the light, " << c.acne
                                   << " did not: shadow acne, the shadow ray hits the surface it leaves (start it "
                                      "off the surface: spawn_ray_to)");
    CHECK_MESSAGE(c.leaks == 0, "expected every point inside the shadow to be blocked by the ball, " << c.leaks
                                    << " saw the light (is the shadow ray bounded by the light, and aimed at it?)");
    CHECK_MESSAGE(c.shadow_points > 20, "expected more than 20 plane points inside the shadow (most hide behind the ball)");
}

TEST_CASE("shadow acne across scales and offsets 1e-3 ... 1e5: neither acne nor leaks with the robust offset, the fixed epsilon's acne shown beside")
{
    std::string table = "scale     offset    lit  shadowed  robust-acne  robust-leaks  fixed-acne(1e-4)\n";
    for (const rt_test::acne_setting& set : rt_test::acne_settings()) {
        const shadow_scene q = set.scene();
        const shadow_count r = count_shadow_errors(q, robust_visible);
        const shadow_count f = count_shadow_errors(q, fixed_epsilon_visible);
        char line[128];
        std::snprintf(line, sizeof line, "%-9.0e %-9.0e %5d %9d %12d %13d %17d\n", set.scale(), set.offset(),
                      r.lit_points, r.shadow_points, r.acne, r.leaks, f.acne);
        table += line;
        CAPTURE(set.scale());
        CAPTURE(set.offset());
        REQUIRE_MESSAGE(r.lit_points > 3000, "expected more than 3000 plane points outside the shadow (the scene's geometry)");
        CHECK_MESSAGE(r.acne == 0, "expected no acne: " << r.acne << " points outside the shadow did not see the light "
                                   "(the shadow ray's start must move with the hit point's rounding error: spawn_ray_to)");
        CHECK_MESSAGE(r.shadow_points > 20, "expected more than 20 plane points inside the shadow");
        CHECK_MESSAGE(r.leaks == 0, "expected no leaks: " << r.leaks << " points inside the shadow saw the light "
                                    "(the offset must not carry the shadow ray past the ball; and the segment must "
                                    "reach the light: spawn_ray_to's t is 1 at the light, so bound any_hit by "
                                    "1 - shadow_epsilon, not by the distance)");
    }
    MESSAGE(table); // the fixed epsilon's acne column: library_shadows_fixed_epsilon checks it, not this suite
}

TEST_CASE("only occluders between the point and the light cast shadows")
{
    rt::scene s;
    rt::triangle floor_a, floor_b;
    floor_a.a = {-5, 0, -5};
    floor_a.b = {5, 0, 5};
    floor_a.c = {5, 0, -5};
    floor_b.a = {-5, 0, -5};
    floor_b.b = {-5, 0, 5};
    floor_b.c = {5, 0, 5};
    s.shapes.emplace_back(floor_a);
    s.shapes.emplace_back(floor_b);
    rt::sphere beyond; // above the light: not between the floor and the light
    beyond.center = {0, 6, 0};
    beyond.radius = 0.5f;
    s.shapes.emplace_back(beyond);
    rt::light bulb;
    bulb.position = {0, 4, 0};
    const rt::accelerator accel(s);
    rt::hit_record hit;
    REQUIRE_MESSAGE(accel.closest_hit(rt::ray{rt::vec3(0.2f, 3, 0.2f), rt::vec3(0, -1, 0)}, 0, 100, hit),
                    "expected the ray straight down to hit the floor (the library's accelerator)");
    CHECK_MESSAGE(rt::light_visible(accel, hit, rt::sample_light(bulb, hit.point)),
                  "expected the point light at (0, 4, 0) visible from the floor: the sphere at height 6 is beyond "
                  "the light (bound the shadow ray at the light: t < 1 - shadow_epsilon on the segment)");
    // a directional light straight down is blocked by the same sphere (it is infinitely far)
    rt::light sun;
    sun.kind = rt::light_kind::directional;
    sun.direction = {0, -1, 0};
    CHECK_FALSE_MESSAGE(rt::light_visible(accel, hit, rt::sample_light(sun, hit.point)),
                        "expected a directional light straight down blocked by the sphere above: a directional "
                        "light is infinitely far, so its shadow ray is unbounded");
    // and a sphere between the floor and the point light blocks it
    rt::sphere between;
    between.center = {0.2f, 2, 0.2f};
    between.radius = 0.3f;
    s.shapes.emplace_back(between);
    const rt::accelerator accel2(s);
    CHECK_FALSE_MESSAGE(rt::light_visible(accel2, hit, rt::sample_light(bulb, hit.point)),
                        "expected the point light blocked by the sphere between the floor and the light");
}
