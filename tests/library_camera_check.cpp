// library_camera_check.cpp - rt::make_ray_generator (include/rt/camera/camera.hpp)
// refuses a camera built in code that a scene file could not hold: an rt::error
// in words, never rays of NaN. It calls the stage-02 frame: in a kit where that
// exercise is not done yet, its rt::exercise_not_done ends the case, which the
// library suites count skipped (tests/doctest_main.cpp).
#include "rt_doctest.hpp"

#include <cmath>
#include <string>

#include <rt/camera/camera.hpp>
#include <rt/core/error.hpp>

namespace {

/// The message make_ray_generator gives for `cam`, or "" when it accepts it.
std::string refusal(const rt::camera& cam, int nx = 64, int ny = 48)
{
    try {
        const rt::ray_generator gen = rt::make_ray_generator(cam, nx, ny);
        (void)gen;
        return std::string();
    } catch (const rt::error& e) {
        return std::string(e.what());
    }
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

} // namespace

TEST_CASE("camera check: a camera a scene file could hold is accepted, with finite rays")
{
    rt::camera cam;
    cam.eye = rt::vec3(0, 1, 5);
    cam.look_at = rt::vec3(0, 0, 0);
    cam.fov_degrees = rt::real(40);
    const std::string message = refusal(cam);
    INFO("make_ray_generator refused a valid camera: " << message);
    CHECK(message.empty());
}

TEST_CASE("camera check: a camera with no frame, window or focal distance is an rt::error naming the cause")
{
    struct bad_case {
        const char* what;
        rt::camera cam;
        const char* words;
    };
    rt::camera base;
    base.eye = rt::vec3(0, 1, 5);
    base.look_at = rt::vec3(0, 0, 0);
    rt::camera at_eye = base, parallel = base, fov0 = base, fov180 = base, empty = base, focal0 = base, nan_eye = base;
    at_eye.look_at = at_eye.eye;
    parallel.up = base.look_at - base.eye;
    fov0.fov_degrees = rt::real(0);
    fov180.fov_degrees = rt::real(180);
    empty.plane = rt::window{1, 1, -1, 1};
    focal0.focal_distance = 0;
    nan_eye.eye.x = std::nanf("");
    const bad_case cases[] = {
        {"eye at look_at", at_eye, "eye must differ from look_at"},
        {"up parallel to the view", parallel, "not be parallel"},
        {"field of view 0", fov0, "(0, 180) degrees"},
        {"field of view 180", fov180, "(0, 180) degrees"},
        {"an empty window", empty, "l < r"},
        {"focal distance 0", focal0, "focal distance > 0"},
        {"a NaN eye", nan_eye, "finite eye"},
    };
    for (const bad_case& c : cases) {
        const std::string message = refusal(c.cam);
        // (std::string: doctest's INFO shows a const char* as an address)
        INFO("camera with " << std::string(c.what) << ": expected an rt::error containing '" << std::string(c.words)
                            << "', got '" << message << "'");
        CHECK(has(message, c.words));
    }
    rt::camera fine = base;
    const std::string no_pixels = refusal(fine, 0, 48);
    INFO("a 0 x 48 image: expected an rt::error naming the size, got '" << no_pixels << "'");
    CHECK(has(no_pixels, "at least 1 x 1 pixels"));
}
