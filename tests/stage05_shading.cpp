// Stage 05 - shading: Blinn-Phong, Fundamentals of Computer Graphics 4th ed., sec. 4.5.
//
// Every expected value is the formula
//     L = ka Ia + sum_i [ kd I_i max(0, n.l_i) + ks I_i max(0, n.h_i)^p ]
// evaluated by hand in double in the test, from the geometry of the case (a
// unit sphere, an orthographic view along -z). Rays and scenes are made here:
// nothing of stages 01, 02 or 04 is called, only the library's stable sphere
// intersection (unmarked) and this stage's shading.
#include "rt_doctest.hpp"
#include "shading_scene.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include <rt/core/hit_record.hpp>
#include <rt/scene/scene.hpp>
#include <rt/shading/shading.hpp>
#include <rt/intersection/sphere_stable.hpp>

namespace {

using rt_test::always_visible;
using rt_test::one_sphere_scene;
using rt_test::shade_at;
using rt_test::test_material;

/// Whether got is (r, g, b) within eps; each channel a CHECK that prints both colors.
bool check_color(const rt::color& got, double r, double g, double b, double eps = 1e-5)
{
    INFO("expected the color " << rt_doctest::text(rt::vec3(rt::real(r), rt::real(g), rt::real(b))) << ", found "
                                << rt_doctest::text(got));
    const bool ok_r = got.r == doctest::Approx(r).epsilon(eps);
    const bool ok_g = got.g == doctest::Approx(g).epsilon(eps);
    const bool ok_b = got.b == doctest::Approx(b).epsilon(eps);
    CHECK(got.r == doctest::Approx(r).epsilon(eps));
    CHECK(got.g == doctest::Approx(g).epsilon(eps));
    CHECK(got.b == doctest::Approx(b).epsilon(eps));
    return ok_r && ok_g && ok_b;
}

} // namespace

TEST_CASE("blinn_phong where h = n: the highlight is ks I exactly, so h = (v + l) / |v + l| must be a unit vector")
{
    // FCG 4th ed., sec. 4.5.2: L = kd I max(0, n.l) + ks I max(0, n.h)^p with the unit
    // half vector h = (v + l) / |v + l|. Here v and l are unit vectors and n = h.
    const rt::material m = test_material();
    const rt::color I(1.0f, 0.9f, 0.8f);
    const rt::vec3 v(0, 0, 1), l = glm::normalize(rt::vec3(1, 0, 1)), n = glm::normalize(v + l);
    const double nl = double(glm::dot(n, l)); // cos 22.5 degrees
    const rt::color L = rt::blinn_phong(m, n, v, l, I);
    const double red = 0.7 * 1.0 * nl + 0.4 * 1.0;
    // a hint for the two likeliest causes, told apart by the red channel found
    const double unnormalised = std::pow(double(glm::length(v + l)), 20);
    std::ostringstream hint;
    if (double(L.r) > 2 * red)
        hint << "; with h = v + l unnormalised n.h = |v + l| = " << double(glm::length(v + l))
             << " and the highlight is " << unnormalised << " times too bright: normalise the half vector";
    else if (double(L.r) < 0.5 * red)
        hint << "; found (almost) no light: l is the unit direction from the point towards the light, and here "
                "n.l = cos 22.5 degrees > 0";
    else if (std::abs(double(L.r) - red - 0.2) < 1e-3)
        hint << "; found ka I = (0.2, 0.09, 0.04) more: blinn_phong has no ambient term (the caller adds ka Ia "
                "once)";
    INFO("n = h: n.h = 1, so the specular term is ks I = (0.4, 0.36, 0.32), and the diffuse term kd I n.l"
         << hint.str());
    check_color(L, red, 0.5 * 0.9 * nl + 0.4 * 0.9, 0.3 * 0.8 * nl + 0.4 * 0.8, 1e-5);
}

TEST_CASE("blinn_phong: the highlight is (n.h)^p with the half vector h, not Phong's (R.v)^p")
{
    // Specular only (kd = 0, ks = 1, I = 1), n = v = +z and a light 60 degrees
    // from n: h = (v + l) / |v + l| lies halfway, 30 degrees from n, so n.h =
    // cos 30 degrees = 0.866 (FCG 4th ed., sec. 4.5.3). Phong's mirror direction
    // R = 2 (n.l) n - l lies 60 degrees from v on the other side: R.v = cos 60
    // degrees = 0.5. The two models agree only where h = n (R = v).
    rt::material m;
    m.kd = rt::color(0.0f);
    m.ks = rt::color(1.0f);
    const rt::vec3 n(0, 0, 1), v(0, 0, 1);
    const rt::vec3 l(std::sqrt(rt::real(3)) / 2, 0, rt::real(0.5));
    const double nh = std::sqrt(3.0) / 2, rv = 0.5;
    for (const double p : {1.0, 10.0}) {
        m.p = rt::real(p);
        const double found = double(rt::blinn_phong(m, n, v, l, rt::color(1.0f)).r);
        const double blinn = std::pow(nh, p), phong = std::pow(rv, p);
        CAPTURE(p);
        std::ostringstream hint;
        if (std::abs(found - phong) < 1e-4)
            hint << ": the highlight follows Phong's R.v (R = 2 (n.l) n - l, R.v = 0.5 here), expected "
                    "Blinn-Phong's n.h with h = normalize(l + v)";
        else if (std::abs(found - nh) < 1e-4 && p != 1)
            hint << ": that is n.h without the exponent p";
        INFO("specular only, n = v = +z, l 60 degrees from n: h = normalize(l + v) is 30 degrees from n, so the "
             "highlight is ks I (n.h)^p = cos(30 degrees)^"
             << p << " = " << blinn << ", found " << found << hint.str());
        CHECK(found == doctest::Approx(blinn).epsilon(1e-5));
    }
}

TEST_CASE("one sphere, one directional light, orthographic view: pixels equal the formula by hand")
{
    const rt::scene s = one_sphere_scene();
    // Orthographic pixel centres of an 8 x 8 image over the window [-1, 1]^2:
    // u = -1 + 2 (i + 0.5) / 8. The sphere point under (u, v) is (u, v, nz),
    // nz = sqrt(1 - u^2 - v^2), with normal n = (u, v, nz); v = l = h = +z, so
    // n.l = n.h = nz and L = ka Ia + kd I nz + ks I nz^20.
    const double ka[3] = {0.2, 0.1, 0.05}, kd[3] = {0.7, 0.5, 0.3}, ks = 0.4, I[3] = {1.0, 0.9, 0.8}, Ia = 0.3;
    int pixels_on_sphere = 0;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
            const double u = -1 + 2 * (i + 0.5) / 8, v = -1 + 2 * (j + 0.5) / 8;
            if (u * u + v * v >= 1)
                continue;
            ++pixels_on_sphere;
            const double nz = std::sqrt(1 - u * u - v * v);
            double expected[3];
            for (int c = 0; c < 3; ++c)
                expected[c] = ka[c] * Ia + kd[c] * I[c] * nz + ks * I[c] * std::pow(nz, 20);
            INFO("the pixel centre (u, v) = (" << u << ", " << v << ") of the window: the sphere point under it has "
                 "normal n = (u, v, nz), nz = " << nz << "; the viewer and the light are along +z (v = l = h = +z), "
                 "so L = ka Ia + kd I nz + ks I nz^20 (FCG 4th ed., sec. 4.5.2)");
            if (!check_color(shade_at(s, u, v), expected[0], expected[1], expected[2], 1e-4))
                return; // one pixel shows the cause; the other 51 would repeat it
        }
    CHECK_MESSAGE(pixels_on_sphere == 52, "expected 52 of the 64 pixel centres inside the sphere's disc (counted by hand)");
}

TEST_CASE("the ray through the sphere's centre: n = l = v = h, every term at its maximum")
{
    const rt::color L = shade_at(one_sphere_scene(), 0, 0);
    // 0.2*0.3 + 0.7*1 + 0.4*1 = 1.16; 0.1*0.3 + 0.5*0.9 + 0.4*0.9 = 0.84; 0.05*0.3 + 0.3*0.8 + 0.4*0.8 = 0.575
    check_color(L, 1.16, 0.84, 0.575);
}

TEST_CASE("each term alone: ambient only, a light switched off, a light behind the surface")
{
    rt::scene s = one_sphere_scene();
    SUBCASE("ambient only (no lights): L = ka Ia everywhere")
    {
        s.lights.clear();
        check_color(shade_at(s, 0.3, -0.2), 0.2 * 0.3, 0.1 * 0.3, 0.05 * 0.3);
    }
    SUBCASE("a light of intensity 0 adds nothing")
    {
        s.lights[0].intensity = rt::color(0.0f);
        check_color(shade_at(s, 0.5, 0.5), 0.06, 0.03, 0.015);
    }
    SUBCASE("a light behind the surface adds neither diffuse nor specular")
    {
        s.lights[0].direction = {0, 0, 1}; // shines along +z: l = -z, behind the visible side
        check_color(shade_at(s, 0.1, 0.2), 0.06, 0.03, 0.015);
    }
    SUBCASE("diffuse only: ks = 0, Ia = 0, a light from the side at 60 degrees from n")
    {
        s.materials[0].ks = rt::color(0.0f);
        s.ambient = rt::color(0.0f);
        // at the centre pixel n = +z; l = (sin 60, 0, cos 60): n.l = 0.5
        s.lights[0].direction = -rt::vec3(std::sqrt(rt::real(3)) / 2, 0, rt::real(0.5));
        INFO("kd I n.l = (0.35, 0.225, 0.12) alone: found 0, l points the wrong way (l is the unit direction "
             "from the point towards the light); found ka I more, blinn_phong added an ambient term (the caller "
             "adds ka Ia once)");
        check_color(shade_at(s, 0, 0), 0.7 * 1.0 * 0.5, 0.5 * 0.9 * 0.5, 0.3 * 0.8 * 0.5);
    }
    SUBCASE("specular only: kd = 0, Ia = 0, the same side light: n.h = cos 30 degrees")
    {
        s.materials[0].kd = rt::color(0.0f);
        s.ambient = rt::color(0.0f);
        s.lights[0].direction = -rt::vec3(std::sqrt(rt::real(3)) / 2, 0, rt::real(0.5));
        const double spec = 0.4 * std::pow(std::cos(3.14159265358979323846 / 6), 20);
        check_color(shade_at(s, 0, 0), spec * 1.0, spec * 0.9, spec * 0.8);
    }
}

TEST_CASE("lights add: two lights give the sum of each alone")
{
    rt::scene one = one_sphere_scene();
    rt::scene other = one_sphere_scene();
    other.lights[0].direction = {-1, -1, -1};
    other.lights[0].intensity = {0.2f, 0.5f, 0.1f};
    rt::scene both = one;
    both.lights.push_back(other.lights[0]);
    const rt::color ambient = test_material().ka * one.ambient;
    const rt::color a = shade_at(one, 0.2, 0.3), b = shade_at(other, 0.2, 0.3), sum = shade_at(both, 0.2, 0.3);
    check_color(sum, a.r + b.r - ambient.r, a.g + b.g - ambient.g, a.b + b.b - ambient.b);
}

TEST_CASE("point lights: no falloff by default, as in the book, 1/r^2 with the option")
{
    rt::scene s = one_sphere_scene();
    s.lights[0].kind = rt::light_kind::point;
    s.lights[0].position = {0, 0, 5}; // 4 units above the top point (0, 0, 1)
    s.materials[0].ks = rt::color(0.0f);
    s.ambient = rt::color(0.0f);
    const rt::ray r{rt::vec3(0, 0, 10), rt::vec3(0, 0, -1)};
    rt::hit_record hit;
    REQUIRE_MESSAGE(rt::hit_sphere(std::get<rt::sphere>(s.shapes[0]), r, 0, 100, hit),
                    "expected the test's ray to hit the sphere (the library's hit_sphere: a fault of the test scene, not of your shading)");
    check_color(rt::direct_lighting(s, hit, r.direction, always_visible), 0.7, 0.45, 0.24);
    rt::shading_options falloff;
    falloff.light_falloff = true;
    check_color(rt::direct_lighting(s, hit, r.direction, always_visible, falloff), 0.7 / 16, 0.45 / 16, 0.24 / 16);
}

TEST_CASE("blinn_phong: the highlight peaks at ks I where h = n, and never goes negative")
{
    rt::material m;
    m.kd = rt::color(0.0f);
    m.ks = {0.5f, 0.25f, 1.0f};
    m.p = 100;
    const rt::vec3 n(0, 1, 0);
    const rt::vec3 l = glm::normalize(rt::vec3(1, 1, 0));
    const rt::vec3 mirror = glm::normalize(rt::vec3(-1, 1, 0)); // v = the mirror direction of l: h = n
    check_color(rt::blinn_phong(m, n, mirror, l, rt::color(2.0f)), 1.0, 0.5, 2.0);
    {
        // away from the mirror direction the highlight falls: n.h < 1
        const rt::color off = rt::blinn_phong(m, n, glm::normalize(rt::vec3(-1, 2, 0)), l, rt::color(2.0f));
        INFO("away from the mirror direction n.h < 1, so the highlight ks I (n.h)^p falls below its peak ks I = 1 "
             "(red) but stays positive, found " << off.r);
        CHECK(off.r < 1.0f);
        CHECK(off.r > 0.0f);
    }
    {
        // n.h < 0 (a viewer far below the light's mirror direction) while n.l > 0:
        // max(0, n.h)^p is 0; an odd p shows an unclamped cosine as a negative color
        m.p = 3;
        const rt::vec3 light = glm::normalize(rt::vec3(1, rt::real(0.2), 0));
        const rt::vec3 viewer = glm::normalize(rt::vec3(-1, -1, 0));
        const rt::color found = rt::blinn_phong(m, n, viewer, light, rt::color(1.0f));
        // Phong's mirror direction R = 2 (n.l) n - l is 56 degrees from the viewer here: R.v = 0.55 > 0
        const rt::vec3 R = 2 * glm::dot(n, light) * n - light;
        const double phong = 0.5 * std::pow(double(glm::dot(R, viewer)), 3);
        const bool follows_phong = std::abs(double(found.r) - phong) < 1e-4;
        INFO("specular only, n.l = " << double(glm::dot(n, light)) << " > 0 but n.h = "
             << double(glm::dot(n, glm::normalize(light + viewer))) << " < 0: "
             << std::string(follows_phong ? "found ks (R.v)^p: the highlight follows Phong's R.v, expected "
                                            "Blinn-Phong's n.h with h = normalize(l + v)"
                                          : "clamp n.h at 0, max(0, n.h)^p"));
        check_color(found, 0, 0, 0);
    }
    // a light below the surface: n.l < 0 clamps the diffuse term to 0
    m.kd = rt::color(1.0f);
    m.ks = rt::color(0.0f);
    const rt::color below = rt::blinn_phong(m, n, n, glm::normalize(rt::vec3(1, -1, 0)), rt::color(1.0f));
    INFO("diffuse only, a light 45 degrees below the surface: n.l = -0.707 clamps to 0, max(0, n.l)");
    check_color(below, 0, 0, 0);
}

