// The viewer's parts that need no window: the camera controls and the
// progressive renderer (ctest label `viewer`; the window itself is tested
// under Xvfb by xvfb_test.cmake).
//
// Expected values are worked out by hand: orbit angles and distances, the
// pixel a point projects to after a pan, the levels of a view; the progressive
// renderer's images are compared with rt::render's for the same options, bit
// for bit.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <rt/camera/camera.hpp>
#include <rt/core/image.hpp>
#include <rt/rendering/render_setup.hpp>
#include <rt/rendering/renderer.hpp>
#include <rt/rendering/sampler.hpp>
#include <rt/scene/scene.hpp>

#include "camera_control.hpp"
#include "inspector.hpp"
#include "progressive.hpp"
#include "script.hpp"

namespace {

const rt::real pi = rt::real(3.14159265358979323846);

rt::camera front_camera()
{
    rt::camera cam;
    cam.eye = rt::vec3(0, 0, 5);
    cam.look_at = rt::vec3(0, 0, 0);
    cam.up = rt::vec3(0, 1, 0);
    cam.fov_degrees = rt::real(60);
    return cam;
}

/// The film position (pixels from the bottom-left) where point p appears, for a perspective camera.
rt::vec2 project(const rt::camera& cam, const rt::vec3& p, int nx, int ny)
{
    const rt::ray_generator gen = rt::make_ray_generator(cam, nx, ny);
    const rt::vec3 q = p - gen.e;
    const rt::real depth = -glm::dot(q, gen.basis.w);
    // the ray through film (x, y) has direction u u + v v - d w; scale q to depth d
    const rt::real u = glm::dot(q, gen.basis.u) * gen.d / depth;
    const rt::real v = glm::dot(q, gen.basis.v) * gen.d / depth;
    return rt::vec2((u - gen.plane.l) / (gen.plane.r - gen.plane.l) * rt::real(nx),
                    (v - gen.plane.b) / (gen.plane.t - gen.plane.b) * rt::real(ny));
}

/// The angle between the eye offset and the up vector, in degrees.
rt::real polar_degrees(const rt::camera& cam)
{
    const rt::vec3 offset = glm::normalize(cam.eye - cam.look_at);
    return std::acos(glm::dot(offset, glm::normalize(cam.up))) * 180 / pi;
}

/// A radiance function of the film position alone: exact and cheap.
rt::radiance_function film_pattern()
{
    return [](const rt::ray&, rt::sample_context& ctx) {
        return rt::color(float(std::sin(0.3 * double(ctx.film.x))), float(ctx.film.y) / 40.0f,
                         float(ctx.x % 3) / 2.0f);
    };
}

viewer::view small_view()
{
    viewer::view v;
    v.cam = front_camera();
    v.width = 67; // not a multiple of the 32-pixel tiles
    v.height = 41;
    v.aov = rt::aov_kind::rays;
    v.samples_per_pixel = 16;
    v.reconstruction = rt::make_filter(rt::filter_kind::mitchell); // reaches 2 pixels across band borders
    v.threads = 2;
    v.seed = 99;
    return v;
}

/// Waits (up to a minute: a guard against a hang, not a timing) until the view of `generation` finishes.
viewer::status wait_until_finished(viewer::progressive_renderer& renderer, std::uint64_t generation, rt::image& shown)
{
    viewer::status now;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
        renderer.take(shown, now);
        if (now.generation == generation && (now.finished || !now.error.empty()))
            return now;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    FAIL("the view did not finish within a minute");
    return now;
}

bool same_pixels(const rt::image& a, const rt::image& b)
{
    return a.width == b.width && a.height == b.height && a.pixels == b.pixels;
}

} // namespace

TEST_CASE("orbit: dragging right turns the scene right about the up vector, keeping the distance")
{
    const rt::camera cam = front_camera();
    // 90 degrees of turn: 90 / orbit_degrees_per_pixel pixels
    const rt::real pixels = 90 / viewer::orbit_degrees_per_pixel;
    const rt::camera turned = viewer::orbit(cam, pixels, 0);
    // the scene turns right, so the eye goes left: from +z to -x
    CHECK(turned.eye.x == doctest::Approx(-5).epsilon(1e-5));
    CHECK(turned.eye.y == doctest::Approx(0).epsilon(1e-5));
    CHECK(turned.eye.z == doctest::Approx(0).epsilon(1e-5));
    CHECK(turned.look_at == cam.look_at);
    CHECK(turned.up == cam.up);
    CHECK(glm::length(turned.eye - turned.look_at) == doctest::Approx(5).epsilon(1e-6));
    // four quarter turns come back
    const rt::camera around = viewer::orbit(viewer::orbit(viewer::orbit(turned, pixels, 0), pixels, 0), pixels, 0);
    CHECK(glm::length(around.eye - cam.eye) < 1e-4);
}

TEST_CASE("orbit: dragging down looks from above, and the tilt stops short of the up vector")
{
    const rt::camera cam = front_camera(); // polar angle 90 degrees
    const rt::camera higher = viewer::orbit(cam, 0, 30 / viewer::orbit_degrees_per_pixel);
    CHECK(polar_degrees(higher) == doctest::Approx(60).epsilon(1e-4));
    CHECK(higher.eye.y > 0);
    CHECK(glm::length(higher.eye - higher.look_at) == doctest::Approx(5).epsilon(1e-6));
    // far past the pole: stopped at the margin, and the camera frame stays defined
    const rt::camera top = viewer::orbit(cam, 0, 10000);
    CHECK(polar_degrees(top) == doctest::Approx(viewer::pole_margin_degrees).epsilon(1e-3));
    const rt::frame f = rt::make_frame(top.eye, top.look_at, top.up);
    CHECK(std::isfinite(f.u.x));
    CHECK(glm::length(f.u) == doctest::Approx(1));
    const rt::camera bottom = viewer::orbit(cam, 0, -10000);
    CHECK(polar_degrees(bottom) == doctest::Approx(180 - viewer::pole_margin_degrees).epsilon(1e-3));
}

TEST_CASE("pan: the point at the look-at depth follows the mouse pixel for pixel")
{
    const int nx = 200, ny = 100;
    const rt::camera cam = front_camera();
    // a point in the look-at plane, off centre
    const rt::vec3 p(rt::real(0.7), rt::real(-0.4), 0);
    const rt::vec2 before = project(cam, p, nx, ny);
    const rt::camera moved = viewer::pan(cam, 13, 7, nx, ny); // 13 right, 7 down (screen y grows downwards)
    const rt::vec2 after = project(moved, p, nx, ny);
    CHECK(after.x - before.x == doctest::Approx(13).epsilon(1e-4));
    CHECK(after.y - before.y == doctest::Approx(-7).epsilon(1e-4)); // film y grows upwards
    // the view direction is kept
    CHECK(glm::length(glm::normalize(moved.look_at - moved.eye) - glm::normalize(cam.look_at - cam.eye)) < 1e-6);
    // an orthographic camera: the same, with the window's scale
    rt::camera flat = front_camera();
    flat.kind = rt::projection::orthographic;
    flat.fov_degrees.reset();
    flat.plane = rt::window{-2, 2, -1, 1}; // 4 / 200 = 2 / 100 = 0.02 units a pixel
    const rt::camera flat_moved = viewer::pan(flat, 10, 0, nx, ny);
    CHECK(flat_moved.eye.x == doctest::Approx(-0.2));
    CHECK(flat_moved.look_at.x == doctest::Approx(-0.2));
}

TEST_CASE("zoom: each wheel step scales the distance, or an orthographic window, by zoom_step")
{
    const rt::camera cam = front_camera();
    const rt::camera closer = viewer::zoom(cam, 2, 100, 100);
    CHECK(glm::length(closer.eye - closer.look_at) == doctest::Approx(5 * 0.9 * 0.9));
    CHECK(closer.look_at == cam.look_at);
    const rt::camera back = viewer::zoom(closer, -2, 100, 100);
    CHECK(glm::length(back.eye - cam.eye) < 1e-5);
    rt::camera flat = front_camera();
    flat.kind = rt::projection::orthographic;
    flat.fov_degrees.reset();
    flat.plane = rt::window{-1, 3, -2, 2};
    const rt::camera flat_closer = viewer::zoom(flat, 1, 100, 100);
    REQUIRE(flat_closer.plane.has_value());
    CHECK(flat_closer.plane->l == doctest::Approx(1 - 2 * 0.9)); // about the centre (1, 0)
    CHECK(flat_closer.plane->r == doctest::Approx(1 + 2 * 0.9));
    CHECK(flat_closer.plane->b == doctest::Approx(-1.8));
    CHECK(flat_closer.plane->t == doctest::Approx(1.8));
    CHECK(flat_closer.eye == flat.eye);
}

TEST_CASE("levels: a preview, then 1, 4, 16 ... samples per pixel up to the view's")
{
    viewer::view v;
    v.samples_per_pixel = 16;
    std::vector<viewer::level> levels = viewer::plan_levels(v);
    REQUIRE(levels.size() == 4);
    CHECK(levels[0].coarse());
    CHECK(levels[1].samples_per_pixel == 1);
    CHECK(levels[1].sampler == rt::sampler_kind::center); // stage08_output's default for 1 spp
    CHECK(levels[2].samples_per_pixel == 4);
    CHECK(levels[2].sampler == rt::sampler_kind::jittered);
    CHECK(levels[3].samples_per_pixel == 16);

    v.samples_per_pixel = 20; // 1, 4, 16, 20 (jittered 20 = 5 x 4)
    levels = viewer::plan_levels(v);
    REQUIRE(levels.size() == 5);
    CHECK(levels[4].samples_per_pixel == 20);

    v.samples_per_pixel = 1;
    levels = viewer::plan_levels(v);
    REQUIRE(levels.size() == 2);
    CHECK(levels[1].samples_per_pixel == 1);

    // the centre sampler gives 1 sample whatever is asked: one full level, with the asked count
    v.samples_per_pixel = 64;
    v.sampler = rt::sampler_kind::center;
    levels = viewer::plan_levels(v);
    REQUIRE(levels.size() == 2);
    CHECK(levels[1].samples_per_pixel == 64);
    CHECK(levels[1].sampler == rt::sampler_kind::center);

    // grid 16 and grid 17 (5 x 4 = 20) differ; 4 (2 x 2) and 3 (2 x 2) would not
    v.sampler = rt::sampler_kind::grid;
    v.samples_per_pixel = 3;
    levels = viewer::plan_levels(v);
    REQUIRE(levels.size() == 3); // preview, 1, 3 (4 samples)
    CHECK(levels[2].samples_per_pixel == 3);
}

TEST_CASE("every full level of the progressive render is rt::render's image for its options, bit for bit")
{
    const viewer::view v = small_view();
    const rt::radiance_function pattern = film_pattern();
    viewer::progressive_renderer renderer(rt::scene{}, [&](const rt::scene&, rt::aov_kind) { return pattern; });
    const std::uint64_t generation = renderer.start(v);
    rt::image shown;
    const viewer::status done = wait_until_finished(renderer, generation, shown);
    CHECK(done.error.empty());
    CHECK(done.finished);
    CHECK(done.levels_total == 4);
    CHECK(done.levels_done == 4);
    CHECK(done.samples_per_pixel == 16);
    // 67 x 41 pixels at 1 + 4 + 16 samples, a preview of 9 x 6, and the border samples of the
    // Mitchell filter (2 pixels each side of every band): at least the pixels' own samples
    CHECK(done.rays >= std::uint64_t(67 * 41 * 21 + 9 * 6));

    const std::vector<viewer::level> levels = viewer::plan_levels(v);
    const rt::ray_source rays = rt::camera_rays(v.cam, v.width, v.height);
    const rt::render_result full = rt::render(viewer::level_options(v, levels.back()), rays, pattern);
    CHECK(same_pixels(shown, full.pixels));
    const std::optional<viewer::completed_image> saved = renderer.completed();
    REQUIRE(saved.has_value());
    CHECK(saved->pass.samples_per_pixel == 16);
    CHECK(saved->generation == generation);
    CHECK(same_pixels(saved->pixels, full.pixels));
}

TEST_CASE("the path-traced view refines level by level into rt::render's image of stage 11's path tracer, bit for bit")
{
    // a glowing ball (seen from both sides) in a grey sky, stage 11's path tracer
    rt::scene s;
    rt::material glow;
    glow.kd = rt::color(0.5f);
    glow.emission = rt::color(1.0f);
    s.materials.push_back(glow);
    s.shapes.push_back(rt::sphere{rt::vec3(0), 1, 0});
    s.background = rt::color(0.2f);
    viewer::view v = small_view();
    v.aov = rt::aov_kind::shaded;
    v.path_traced = true;
    viewer::progressive_renderer renderer(s);
    const std::uint64_t generation = renderer.start(v);
    rt::image shown;
    const viewer::status done = wait_until_finished(renderer, generation, shown);
    CHECK(done.error.empty());
    CHECK(done.finished);
    CHECK(done.levels_done == done.levels_total);
    const std::vector<viewer::level> levels = viewer::plan_levels(v);
    const rt::ray_source rays = rt::camera_rays(v.cam, v.width, v.height);
    const rt::render_result full = rt::render(viewer::level_options(v, levels.back()), rays, viewer::path_radiance_of(s));
    CHECK(same_pixels(shown, full.pixels));
    // the ball's middle: its glow 1 plus what it reflects of the sky and of itself
    const rt::color middle = shown.at(v.width / 2, v.height / 2);
    INFO("expected the glowing ball's middle brighter than its glow alone, found " << middle.r);
    CHECK(middle.r > 1.0f);
}

TEST_CASE("the preview shows one ray per 8 x 8 block, through the block's centre")
{
    viewer::view v = small_view();
    v.samples_per_pixel = 1;
    // an orthographic camera whose window is the film: a ray starts at (film x, film y, 1)
    v.cam.kind = rt::projection::orthographic;
    v.cam.fov_degrees.reset();
    v.cam.plane = rt::window{0, 67, 0, 41};
    // the preview's rays pass through block centres 8 i + 4, the full image's through
    // pixel centres i + 1/2: the full level waits here until released, so the preview stays shown
    std::atomic<bool> release{false};
    const rt::radiance_function position = [&](const rt::ray& r, rt::sample_context&) {
        while (r.origin.x != std::floor(r.origin.x) && !release)
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        return rt::color(float(r.origin.x), float(r.origin.y), 0.0f);
    };
    viewer::progressive_renderer renderer(rt::scene{}, [&](const rt::scene&, rt::aov_kind) { return position; });
    const std::uint64_t generation = renderer.start(v);
    rt::image shown;
    viewer::status now;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
        renderer.take(shown, now);
        if (now.generation == generation && now.levels_done >= 1)
            break;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    renderer.take(shown, now);
    REQUIRE(now.levels_done == 1);
    REQUIRE(shown.width == 67);
    REQUIRE(shown.height == 41);
    int wrong = 0;
    for (int y = 0; y < 41; ++y)
        for (int x = 0; x < 67; ++x) {
            const int film_row = 40 - y; // rows from the top, film from the bottom
            const rt::color expected(float(8 * (x / 8) + 4), float(8 * (film_row / 8) + 4), 0.0f);
            if (shown.at(x, y) != expected)
                ++wrong;
        }
    CHECK(wrong == 0);
    release = true; // the destructor cancels the full level
}

TEST_CASE("a new view cancels a long render within moments and is rendered instead")
{
    viewer::view huge = small_view();
    huge.width = 2000;
    huge.height = 2000;
    huge.samples_per_pixel = 65536; // hours of work
    const rt::radiance_function pattern = film_pattern();
    viewer::progressive_renderer renderer(rt::scene{}, [&](const rt::scene&, rt::aov_kind) { return pattern; });
    renderer.start(huge);
    std::this_thread::sleep_for(std::chrono::milliseconds(200)); // let it get going
    const viewer::view v = small_view();
    const std::uint64_t generation = renderer.start(v);
    rt::image shown;
    const viewer::status done = wait_until_finished(renderer, generation, shown);
    CHECK(done.finished);
    CHECK(shown.width == 67);
    const rt::render_result full =
        rt::render(viewer::level_options(v, viewer::plan_levels(v).back()), rt::camera_rays(v.cam, 67, 41), pattern);
    CHECK(same_pixels(shown, full.pixels));
    // and a renderer destroyed in the middle of a long render stops (the test would hang otherwise)
    renderer.start(huge);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
}

TEST_CASE("a failing radiance function stops the view with its message, and the next view renders")
{
    viewer::view v = small_view();
    viewer::progressive_renderer renderer(rt::scene{}, [&](const rt::scene&, rt::aov_kind aov) {
        if (aov == rt::aov_kind::depth)
            throw rt::error("depth is not connected");
        return rt::radiance_function([](const rt::ray&, rt::sample_context& ctx) -> rt::color {
            if (ctx.x == 50 && ctx.y == 30)
                throw rt::error("a bad pixel");
            return rt::color(1.0f);
        });
    });
    rt::image shown;
    viewer::status now = wait_until_finished(renderer, renderer.start(v), shown);
    CHECK(now.error == "a bad pixel");
    CHECK(!now.finished);
    v.aov = rt::aov_kind::depth;
    now = wait_until_finished(renderer, renderer.start(v), shown);
    CHECK(now.error == "depth is not connected");
    CHECK(!renderer.completed().has_value());
}

TEST_CASE("script: commands split at newlines and semicolons, words at blanks, '#' comments")
{
    const std::vector<viewer::script_command> commands =
        viewer::parse_script("orbit 10 -5; zoom 2\n  key ]  # a comment; not a command\nwait;wait 3;; sleep 10\n"
                             "screenshot shot.png; quit",
                             "demo");
    REQUIRE(commands.size() == 8);
    CHECK(commands[0].name == "orbit");
    CHECK(commands[0].arguments == std::vector<std::string>{"10", "-5"});
    CHECK(commands[0].number(1) == -5);
    CHECK(commands[1].name == "zoom");
    CHECK(commands[2].name == "key");
    CHECK(commands[2].arguments == std::vector<std::string>{"]"});
    CHECK(rt::to_string(commands[2].where) == "demo:2:3");
    CHECK(commands[3].name == "wait");
    CHECK(commands[3].arguments.empty());
    CHECK(commands[4].arguments == std::vector<std::string>{"3"});
    CHECK(rt::to_string(commands[4].where) == "demo:3:6");
    CHECK(commands[5].name == "sleep");
    CHECK(commands[6].arguments == std::vector<std::string>{"shot.png"});
    CHECK(commands[7].name == "quit");
    CHECK(viewer::parse_script("").empty());
}

TEST_CASE("script: a bad command is one line with its place, what was expected and what was found")
{
    auto error_of = [](const std::string& text) {
        try {
            viewer::parse_script(text);
        } catch (const rt::error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(error_of("wait\norbi 1 2") == "--script:2:1: expected a command (orbit, pan, zoom, key, click, wait, "
                                       "sleep, screenshot, title, save, args, story, quit), found 'orbi'");
    CHECK(error_of("click 3") == "--script:1:7: expected 2 arguments after 'click', found 1");
    CHECK(error_of("click 3 -1") == "--script:1:9: expected a whole number from 0 to 1000000, found '-1'");
    CHECK(error_of("orbit 1") == "--script:1:7: expected 2 arguments after 'orbit', found 1");
    CHECK(error_of("quit now") == "--script:1:6: expected 0 arguments after 'quit', found 1");
    CHECK(error_of("wait 1 2") == "--script:1:8: expected 1 or 0 argument after 'wait', found 2");
    CHECK(error_of("zoom x") == "--script:1:6: expected a number between -1e6 and 1e6, found 'x'");
    CHECK(error_of("sleep 1.5") == "--script:1:7: expected a whole number from 0 to 1000000, found '1.5'");
    CHECK(error_of("sleep -1") == "--script:1:7: expected a whole number from 0 to 1000000, found '-1'");
}

// --- the ray inspector (inspector.hpp) -------------------------------------------

TEST_CASE("the inspector's projection inverts generate_ray: a point on a pixel's ray shows at that pixel's centre")
{
    for (const rt::projection kind : {rt::projection::perspective, rt::projection::orthographic}) {
        rt::camera cam;
        cam.kind = kind;
        cam.eye = {1, 2, 5};
        cam.look_at = {0, 0.5f, 0};
        cam.up = {0.1f, 1, 0};
        if (kind == rt::projection::perspective)
            cam.fov_degrees = rt::real(50);
        const int nx = 67, ny = 41;
        const rt::ray_generator gen = rt::make_ray_generator(cam, nx, ny);
        for (const int i : {0, 13, 66})
            for (const int j : {0, 20, 40}) {
                const rt::ray r = rt::pixel_ray(gen, i, j);
                for (const rt::real t : {rt::real(0.5), rt::real(3.7), rt::real(40)}) {
                    const std::optional<viewer::window_point> p = viewer::project(gen, r.at(t));
                    CAPTURE(i);
                    CAPTURE(j);
                    CAPTURE(t);
                    REQUIRE(p);
                    // the window's rows count from the top: pixel row ny - 1 - j, centre ny - j - 0.5
                    CHECK(p->x == doctest::Approx(i + 0.5).epsilon(1e-4));
                    CHECK(p->y == doctest::Approx(ny - j - 0.5).epsilon(1e-4));
                }
            }
        if (kind == rt::projection::perspective) {
            CHECK_FALSE(viewer::project(gen, cam.eye + (cam.eye - cam.look_at))); // behind the eye
        }
    }
}

TEST_CASE("the inspector clips a segment to the window, and drops one that misses it")
{
    const auto inside = viewer::clip({10, 10}, {20, 30}, 0, 0, 100, 50);
    REQUIRE(inside);
    CHECK(inside->first.x == 10);
    CHECK(inside->second.y == 30);
    const auto across = viewer::clip({-100, 25}, {200, 25}, 0, 0, 100, 50);
    REQUIRE(across);
    CHECK(across->first.x == doctest::Approx(0));
    CHECK(across->second.x == doctest::Approx(100));
    CHECK_FALSE(viewer::clip({-10, -10}, {-5, 60}, 0, 0, 100, 50));
    CHECK_FALSE(viewer::clip({1e12, 5}, {2e12, 5}, 0, 0, 100, 50));
}

TEST_CASE("the inspector draws each query of a story as a segment of its kind, to its hit, its end or its reach")
{
    rt::camera cam;
    cam.eye = {0, 0, 10};
    cam.look_at = {0, 0, 0};
    const rt::ray_generator gen = rt::make_ray_generator(cam, 64, 48);
    stage::story st;
    auto add = [&](stage::query_record::kind what, const char* role, rt::ray r, bool hit, rt::vec3 point,
                   rt::real tmax) {
        stage::query_record q;
        q.what = what;
        q.role = role;
        q.r = r;
        q.hit = hit;
        q.rec.point = point;
        q.tmax = tmax;
        st.queries.push_back(q);
    };
    const rt::real inf = std::numeric_limits<rt::real>::infinity();
    using kind = stage::query_record::kind;
    add(kind::closest, "camera", rt::ray{cam.eye, {0, 0, -1}}, true, {0, 0, 0}, inf);
    add(kind::any, "shadow (light 0)", rt::ray{{0, 0, 0}, {1, 1, 0}}, false, {}, rt::real(0.9999));
    add(kind::any, "shadow (light 1)", rt::ray{{0, 0, 0}, {-1, 0, 0}}, true, {-0.5f, 0, 0}, rt::real(0.9999));
    add(kind::closest, "reflection 1", rt::ray{{0, 0, 0}, {0, 1, 1}}, false, {}, inf);
    add(kind::closest, "refraction 1", rt::ray{{0, 0, 0}, {0.5f, 0, -1}}, true, {0.5f, 0, -1}, inf);
    const std::vector<viewer::overlay_segment> segs = viewer::story_segments(st, gen, 4);
    REQUIRE(segs.size() == 5);
    CHECK(segs[0].what == viewer::ray_kind::camera);
    CHECK(segs[1].what == viewer::ray_kind::shadow_visible);
    CHECK(segs[2].what == viewer::ray_kind::shadow_blocked);
    CHECK(segs[3].what == viewer::ray_kind::reflection);
    CHECK(segs[4].what == viewer::ray_kind::refraction);
    // the camera ray is seen end on: it starts (clipped just in front of the eye) and ends at the centre
    CHECK(segs[0].a.x == doctest::Approx(32));
    CHECK(segs[0].b.y == doctest::Approx(24));
    CHECK(segs[0].ends_at_hit);
    // the visible shadow ray ends at its light, t = tmax: up and to the right of the centre
    CHECK(segs[1].b.x > 32);
    CHECK(segs[1].b.y < 24);
    CHECK_FALSE(segs[1].ends_at_hit);
    // the blocked one at its blocker, left of the centre
    CHECK(segs[2].b.x < 32);
    CHECK(segs[2].ends_at_hit);
    // the reflection that missed is drawn to its reach, 4 along its unit direction
    const std::optional<viewer::window_point> far = viewer::project(gen, rt::vec3(0, 4, 4) / std::sqrt(rt::real(2)));
    REQUIRE(far);
    CHECK(segs[3].b.y == doctest::Approx(far->y));
}
