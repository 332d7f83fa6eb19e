// library_distribution.cpp - the given part of stage 10: the scene statements
// for area lights, the lens and glossy mirrors; the concentric disk map;
// area lights without random numbers (stages 05-09 see a point light at the
// centre); mirror_direction; the renderer's thin lens, which keeps the plane
// in focus exactly as sharp as a pinhole camera; and the renderer's soft
// shadow, whose pixel average converges to the light's integral. Stage 10's
// exercises are tested in tests/stage10_distribution.cpp.
#include "rt_doctest.hpp"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include <rt/core/error.hpp>
#include <rt/shading/glossy.hpp>
#include <rt/scene/light.hpp>
#include <rt/scene/light_sample.hpp>
#include <rt/rendering/radiance.hpp>
#include <rt/core/random.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/input/scene_loader.hpp>
#include <rt/shading/shading.hpp>
#include <rt/camera/thin_lens.hpp>

namespace {

std::string load_error(const std::string& text)
{
    try {
        (void)rt::load_scene_from_string(text, "s.scene");
    } catch (const rt::error& e) {
        return e.what();
    }
    return "no error";
}

} // namespace

TEST_CASE("the scene file declares rect and sphere lights, a lens and glossy mirrors")
{
    const rt::scene s = rt::load_scene_from_string("camera perspective eye 0 0 5 look_at 0 0 1\n"
                                                   "lens aperture 0.1\n"
                                                   "material brushed km 0.8 0.8 0.8 glossy 0.2\n"
                                                   "light rect corner -1 4 -1 edge1 2 0 0 edge2 0 0 2 intensity 1 1 1\n"
                                                   "light sphere center 3 3 3 radius 0.5 intensity 0.5 0.5 0.5\n");
    REQUIRE(s.lights.size() == 2);
    CHECK(s.lights[0].kind == rt::light_kind::rect);
    CHECK(s.lights[0].edge2.z == doctest::Approx(2));
    CHECK(s.lights[1].kind == rt::light_kind::sphere);
    CHECK(s.lights[1].radius == doctest::Approx(0.5));
    CHECK(s.lens.aperture == doctest::Approx(0.1));
    CHECK(s.lens.focus == doctest::Approx(4)); // no focus: where the camera looks, |look_at - eye|
    CHECK(s.materials[0].glossy == doctest::Approx(0.2));
    CHECK(rt::has_glossy(s));
    CHECK(rt::load_scene_from_string("lens aperture 0.1 focus 2.5\n").lens.focus == doctest::Approx(2.5));
}

TEST_CASE("a lens, an area light or gloss that cannot work is refused with file:line:col and a hint")
{
    CHECK(load_error("camera orthographic eye 0 0 5 look_at 0 0 0\nlens aperture 0.1\n") ==
          "s.scene:2:1: expected a lens in front of a perspective camera, found an orthographic camera; a thin lens "
          "focuses a perspective camera's rays; use aperture 0 or a perspective camera");
    CHECK(load_error("material m kd 1 1 1 glossy 0.2\n") ==
          "s.scene:1:21: expected glossy only with km, found glossy without a mirror; glossy blurs a mirror's "
          "reflection: add km (0.8 0.8 0.8)");
    CHECK(load_error("light rect corner 0 0 0 edge1 1 0 0 edge2 2 0 0\n") ==
          "s.scene:1:1: expected a rect light with an area, found edges that are parallel or zero; edge1 and edge2 are "
          "two sides from the corner, e.g. edge1 1 0 0 edge2 0 0 1");
    CHECK(load_error("light sphere radius 0\n").find("s.scene:1:21: expected a positive radius, found 0") == 0);
    CHECK(load_error("lens focus -1\n").find("s.scene:1:12: expected a positive focus distance, found -1") == 0);
    CHECK(load_error("lens aperture 0.1\nlens aperture 0.2\n").find("s.scene:2:1: expected one lens") == 0);
    CHECK(load_error("light disk\n").find("expected a light type (point, directional, rect or sphere), found 'disk'") !=
          std::string::npos);
}

TEST_CASE("concentric_disk maps the square onto the unit disk, keeping areas")
{
    CHECK(glm::length(rt::concentric_disk(rt::real(0.5), rt::real(0.5))) == doctest::Approx(0));
    // the square's edges go to the circle
    CHECK(glm::length(rt::concentric_disk(0, rt::real(0.3))) == doctest::Approx(1));
    CHECK(glm::length(rt::concentric_disk(rt::real(0.7), 0)) == doctest::Approx(1));
    rt::pcg32 rng(3, 7);
    const int n = 40000;
    int outside = 0, inner = 0;
    for (int k = 0; k < n; ++k) {
        const rt::real xi1 = rng.next_float(), xi2 = rng.next_float();
        const rt::vec2 p = rt::concentric_disk(xi1, xi2);
        outside += glm::length(p) > 1 + 1e-6f ? 1 : 0;
        inner += glm::length(p) < 0.5f ? 1 : 0; // a quarter of the disk's area
    }
    CHECK(outside == 0);
    const double f = double(inner) / n, sigma = std::sqrt(0.25 * 0.75 / n);
    INFO("expected a quarter of the points within radius 1/2, found " << f);
    CHECK(std::fabs(f - 0.25) < 5 * sigma);
}

TEST_CASE("without random numbers an area light is a point light at its centre (stages 05-09)")
{
    rt::light panel;
    panel.kind = rt::light_kind::rect;
    panel.position = rt::vec3(-1, 4, -1);
    panel.edge1 = rt::vec3(2, 0, 0);
    panel.edge2 = rt::vec3(0, 0, 2);
    const rt::light_sample a = rt::sample_light(panel, rt::vec3(0, 1, 0));
    CHECK(a.distance == doctest::Approx(3));
    CHECK(a.l.y == doctest::Approx(1));
    rt::light bulb;
    bulb.kind = rt::light_kind::sphere;
    bulb.position = rt::vec3(0, 5, 0);
    bulb.radius = 1;
    const rt::light_sample b = rt::sample_light(bulb, rt::vec3(0, 1, 0));
    CHECK(b.distance == doctest::Approx(4));
    // with falloff, I / r^2 over the distance to the point drawn
    const rt::light_sample c = rt::sample_light(bulb, rt::vec3(0, 1, 0), true, rt::vec2(0, 0));
    CHECK(c.distance == doctest::Approx(3)); // xi1 = 0: the point of the sphere nearest x
    CHECK(c.intensity.r == doctest::Approx(1.0 / 9));
}

TEST_CASE("mirror_direction: a perfect mirror, and a glossy one without random numbers, reflect exactly, with them above the surface")
{
    const rt::vec3 d = glm::normalize(rt::vec3(1, -1, 0)), n(0, 1, 0);
    rt::material m;
    m.km = rt::color(0.8f);
    rt::pcg32 rng(1, 2);
    rt::shading_options with;
    with.random = &rng;
    const rt::vec3 mirror = rt::mirror_direction(m, d, n, with);
    CHECK(mirror.x == doctest::Approx(d.x));
    CHECK(mirror.y == doctest::Approx(-d.y));
    m.glossy = rt::real(0.5);
    const rt::vec3 still = rt::mirror_direction(m, d, n, rt::shading_options{});
    CHECK(glm::length(still - mirror) < 1e-6);
    // grazing: many perturbed directions would go below the surface; none is returned
    const rt::vec3 grazing = glm::normalize(rt::vec3(1, -0.05f, 0));
    int below = 0, moved = 0;
    for (int k = 0; k < 2000; ++k) {
        const rt::vec3 g = rt::mirror_direction(m, grazing, n, with);
        below += glm::dot(g, n) <= 0 ? 1 : 0;
        moved += glm::length(g - rt::reflect(grazing, n)) > 1e-3f ? 1 : 0;
    }
    CHECK(below == 0);
    CHECK(moved > 1000);
}

TEST_CASE("the renderer's thin lens: a plane in focus comes out exactly as with a pinhole, a plane out of focus blurs")
{
    // a wall at distance `wall` facing the camera, black left of x = 0.1 and
    // white right of it, lit by ambient light only (no direction depends on
    // the lens point): every lens ray of a sample meets the plane in focus at
    // the pinhole ray's point, so with the wall there the images are equal
    const auto image_of = [](double wall, double aperture) {
        const std::string z = std::to_string(-wall);
        rt::scene s = rt::load_scene_from_string(
            "image 24 16\ncamera perspective eye 0 0 0 look_at 0 0 -1 fov 30\nambient 1 1 1\n"
            "material black kd 0 0 0\nmaterial white kd 1 1 1\n"
            "triangle -50 -50 " + z + "  0.1 -50 " + z + "  0.1 50 " + z + " material black\n"
            "triangle -50 -50 " + z + "  0.1 50 " + z + "  -50 50 " + z + " material black\n"
            "triangle 0.1 -50 " + z + "  50 -50 " + z + "  50 50 " + z + " material white\n"
            "triangle 0.1 -50 " + z + "  50 50 " + z + "  0.1 50 " + z + " material white\n");
        s.lens.aperture = rt::real(aperture);
        s.lens.focus = 2;
        rt::render_options o;
        o.width = s.width;
        o.height = s.height;
        o.samples_per_pixel = 16;
        o.threads = 1;
        return rt::render(o, rt::camera_rays(s.cam, s.width, s.height), rt::make_radiance(s, rt::aov_kind::shaded)).pixels;
    };
    const auto differing = [](const rt::image& a, const rt::image& b) {
        int count = 0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x)
                count += std::fabs(a.at(x, y).r - b.at(x, y).r) > 1e-5f ? 1 : 0;
        return count;
    };
    const rt::image pinhole = image_of(2, 0), in_focus = image_of(2, 0.3);
    INFO("pixels that differ with the wall in focus: " << differing(pinhole, in_focus));
    CHECK(differing(pinhole, in_focus) == 0);
    const rt::image far_pinhole = image_of(6, 0), blurred = image_of(6, 0.3);
    INFO("pixels that differ with the wall at 3 times the focus distance: " << differing(far_pinhole, blurred));
    CHECK(differing(far_pinhole, blurred) > 8);
}

TEST_CASE("the renderer's soft shadow: a pixel under a half-hidden square light converges to the light's integral")
{
    // The pixel sees the floor point p = (0, 0, 0) (orthographic, a window of
    // 2e-3 around it), white (kd 1, no ambient), under the square light
    // [-1, 1] x [-1, 1] at height 4 (intensity 1, no falloff); a large
    // triangle at height 2 hides every light point with x < 0. One sample's
    // color is kd I max(0, n.l) for its random light point when that point is
    // visible, so the pixel's mean over N samples tends to
    //     E = (1 / area) integral over the light of [x > 0] 4 / |y - p| dA,
    // computed here by the midpoint rule, and its standard deviation is
    // sqrt((E2 - E^2) / N) with E2 the mean of the square.
    rt::scene s = rt::load_scene_from_string(
        "image 1 1\ncamera orthographic eye 0 1 0 look_at 0 0 0 up 0 0 -1 window -0.001 0.001 -0.001 0.001\n"
        "ambient 0 0 0\nmaterial white ka 0 0 0 kd 1 1 1\nmaterial black ka 0 0 0 kd 0 0 0\n"
        "triangle -50 0 -50  -50 0 50  50 0 50 material white\ntriangle -50 0 -50  50 0 50  50 0 -50 material white\n"
        "triangle 0 2 -1000  -1000 2 0  0 2 1000 material black\n"
        "light rect corner -1 4 -1 edge1 2 0 0 edge2 0 0 2 intensity 1 1 1\n");
    double E = 0, E2 = 0;
    const int n = 1000;
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
            const double x = -1 + 2 * (i + 0.5) / n, z = -1 + 2 * (k + 0.5) / n;
            const double term = x > 0 ? 4 / std::sqrt(x * x + 16 + z * z) : 0;
            E += term;
            E2 += term * term;
        }
    E /= double(n) * n;
    E2 /= double(n) * n;
    rt::render_options o;
    o.width = o.height = 1;
    o.samples_per_pixel = 4096;
    o.threads = 1;
    const rt::image out =
        rt::render(o, rt::camera_rays(s.cam, 1, 1), rt::make_radiance(s, rt::aov_kind::shaded)).pixels;
    const double got = double(out.at(0, 0).r), sigma = std::sqrt((E2 - E * E) / o.samples_per_pixel);
    INFO("expected the pixel to average the half-visible light, " << E << " (5 sigma = " << 5 * sigma << "), found "
                                                                   << got << "; " << (got - E) / sigma << " sigma away");
    CHECK(std::fabs(got - E) < 5 * sigma);
}
