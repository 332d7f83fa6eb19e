// Stage 02 - generate rays, and dump them as an image.
//
// Expected values are worked out by hand from Fundamentals of Computer
// Graphics, 4th ed., sec. 4.3 (eq. 4.1 and the two projections); cameras are
// built here, not loaded, so a stage-01 bug cannot fail these cases.
#include "rt_doctest.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

#include <rt/camera.hpp>
#include <rt/image_io.hpp>
#include <rt/ray_image.hpp>

namespace {

const rt::real tol = rt::real(1e-5);

void check_near(const rt::vec3& got, const rt::vec3& want)
{
    INFO("expected " << rt_doctest::text(want) << ", found " << rt_doctest::text(got));
    CHECK(got.x == doctest::Approx(want.x).epsilon(tol).scale(1));
    CHECK(got.y == doctest::Approx(want.y).epsilon(tol).scale(1));
    CHECK(got.z == doctest::Approx(want.z).epsilon(tol).scale(1));
}

rt::camera looking_down_minus_z(rt::projection kind)
{
    rt::camera cam;
    cam.kind = kind;
    cam.eye = rt::vec3(0, 0, 0);
    cam.look_at = rt::vec3(0, 0, -1);
    cam.up = rt::vec3(0, 1, 0);
    cam.plane = rt::window{-2, 2, -1, 1};
    cam.focal_distance = 1;
    return cam;
}

} // namespace

TEST_CASE("the frame is orthonormal and right-handed, with w pointing away from the view")
{
    const rt::vec3 eyes[] = {{0, 0, 0}, {3, -2, 7}, {-100, 50, 1}};
    const rt::vec3 targets[] = {{0, 0, -1}, {1, 1, 1}, {4, 0, -3}};
    const rt::vec3 ups[] = {{0, 1, 0}, {0, 0, 1}, {0.3f, 1, 0.2f}};
    for (int k = 0; k < 3; ++k) {
        const rt::frame f = rt::make_frame(eyes[k], targets[k], ups[k]);
        CAPTURE(eyes[k]);
        CAPTURE(targets[k]);
        CAPTURE(ups[k]);
        INFO("the frame u = " << rt_doctest::text(f.u) << ", v = " << rt_doctest::text(f.v) << ", w = " << rt_doctest::text(f.w)
             << ": expected unit vectors, pairwise perpendicular, u x v = w, w = (eye - look_at) / |eye - look_at|, "
                "u = (up x w) / |up x w|, v = w x u (FCG 4th ed., sec. 2.4.7 and 4.3)");
        CHECK(glm::length(f.u) == doctest::Approx(1).epsilon(tol));
        CHECK(glm::length(f.v) == doctest::Approx(1).epsilon(tol));
        CHECK(glm::length(f.w) == doctest::Approx(1).epsilon(tol));
        CHECK(std::fabs(glm::dot(f.u, f.v)) < tol);
        CHECK(std::fabs(glm::dot(f.v, f.w)) < tol);
        CHECK(std::fabs(glm::dot(f.w, f.u)) < tol);
        check_near(glm::cross(f.u, f.v), f.w); // right-handed
        // w points from the target back to the eye
        const rt::vec3 back = glm::normalize(eyes[k] - targets[k]);
        check_near(f.w, back);
        // v leans towards up: up . v > 0, and up lies in the v-w plane
        CHECK(glm::dot(ups[k], f.v) > 0);
        CHECK(std::fabs(glm::dot(ups[k], f.u)) < tol);
    }
}

TEST_CASE("the canonical camera has the canonical frame")
{
    const rt::frame f = rt::make_frame({0, 0, 0}, {0, 0, -1}, {0, 1, 0});
    check_near(f.u, {1, 0, 0});
    check_near(f.v, {0, 1, 0});
    check_near(f.w, {0, 0, 1});
}

TEST_CASE("field of view to window keeps the aspect ratio")
{
    // fov 90 at d = 1: t = tan(45 deg) = 1; a 200 x 100 image: r = 2.
    const rt::window w = rt::window_from_fov(90, 1, 200, 100);
    INFO("expected t = d tan(fov / 2), b = -t, r = t nx / ny, l = -r (square pixels): fov 90, d = 1, 200 x 100 "
         "gives t = 1, r = 2");
    CHECK(w.t == doctest::Approx(1));
    CHECK(w.b == doctest::Approx(-1));
    CHECK(w.r == doctest::Approx(2));
    CHECK(w.l == doctest::Approx(-2));
    // fov 60 at d = 3: t = 3 tan(30 deg) = sqrt(3); square image
    const rt::window s = rt::window_from_fov(60, 3, 64, 64);
    INFO("fov 60, d = 3, 64 x 64: t = 3 tan(30 degrees) = sqrt(3) = r (fov is in degrees, the full vertical angle)");
    CHECK(s.t == doctest::Approx(std::sqrt(3.0)));
    CHECK(s.r == doctest::Approx(std::sqrt(3.0)));
    // aspect ratio of the window equals that of the image
    const rt::window tall = rt::window_from_fov(40, 1, 90, 160);
    INFO("a 90 x 160 image: expected the window's width / height to be 90 / 160 (r = t nx / ny)");
    CHECK((tall.r - tall.l) / (tall.t - tall.b) == doctest::Approx(90.0 / 160.0));
}

TEST_CASE("orthographic rays of pixel (0,0), the centre pixel and the last pixel, by hand")
{
    // 4 x 2 image, window [-2, 2] x [-1, 1]: pixel (i, j) centre is at
    // u = -2 + 4 (i + 0.5) / 4 = i - 1.5,  v = -1 + 2 (j + 0.5) / 2 = j - 0.5.
    const rt::ray_generator gen = rt::make_ray_generator(looking_down_minus_z(rt::projection::orthographic), 4, 2);
    {
        const rt::ray first = rt::pixel_ray(gen, 0, 0);
        INFO("pixel (0, 0) is the bottom-left pixel: x counts columns from the left, y rows from the bottom "
             "(FCG 4th ed., sec. 4.3.1), so its ray starts at u = -1.5, v = -0.5; v = +0.5 means rows counted from the top");
        check_near(first.origin, {-1.5, -0.5, 0});
        check_near(first.direction, {0, 0, -1});
    }
    {
        const rt::ray last = rt::pixel_ray(gen, 3, 1);
        INFO("pixel (3, 1) is the top-right pixel (rows counted from the bottom): its ray starts at u = 1.5, v = 0.5");
        check_near(last.origin, {1.5, 0.5, 0});
        check_near(last.direction, {0, 0, -1});
    }
    const rt::ray centre = rt::generate_ray(gen, 2, 1); // the image centre
    INFO("the position (2, 1) in pixels is the image centre: its ray starts at the eye, u = v = 0");
    check_near(centre.origin, {0, 0, 0});
}

TEST_CASE("perspective rays of pixel (0,0), the centre pixel and the last pixel, by hand")
{
    // same window, d = 1: direction = u u + v v - d w = (u, v, -1)
    const rt::ray_generator gen = rt::make_ray_generator(looking_down_minus_z(rt::projection::perspective), 4, 2);
    {
        const rt::ray first = rt::pixel_ray(gen, 0, 0);
        INFO("pixel (0, 0) is the bottom-left pixel (rows counted from the bottom): its ray starts at the eye with "
             "direction (-1.5, -0.5, -1), not normalised (d = -d w + u u + v v)");
        check_near(first.origin, {0, 0, 0});
        check_near(first.direction, {-1.5, -0.5, -1});
    }
    {
        const rt::ray last = rt::pixel_ray(gen, 3, 1);
        INFO("pixel (3, 1) is the top-right pixel (rows counted from the bottom): its direction is (1.5, 0.5, -1)");
        check_near(last.direction, {1.5, 0.5, -1});
    }
    const rt::ray centre = rt::generate_ray(gen, 2, 1);
    INFO("the position (2, 1) in pixels is the image centre: its direction is -d w = (0, 0, -1)");
    check_near(centre.direction, {0, 0, -1});
}

TEST_CASE("a camera elsewhere: rays follow the frame (eye 1 2 3 looking along +x, up +z)")
{
    rt::camera cam = looking_down_minus_z(rt::projection::perspective);
    cam.eye = {1, 2, 3};
    cam.look_at = {5, 2, 3};
    cam.up = {0, 0, 1};
    cam.focal_distance = 2;
    // w = (-1, 0, 0), u = up x w = (0, -1, 0), v = w x u = (0, 0, 1)
    const rt::ray_generator gen = rt::make_ray_generator(cam, 4, 2);
    const rt::ray r = rt::pixel_ray(gen, 3, 1); // u = 1.5, v = 0.5
    check_near(r.origin, {1, 2, 3});
    check_near(r.direction, {2, -1.5, 0.5}); // 1.5 u + 0.5 v - 2 w
}

TEST_CASE("orthographic rays are all parallel, perspective rays all pass through the eye")
{
    rt::camera cam;
    cam.eye = {2, 1, 4};
    cam.look_at = {0, 0, 0};
    cam.fov_degrees = 50;
    cam.kind = rt::projection::perspective;
    const rt::ray_generator persp = rt::make_ray_generator(cam, 17, 9);
    cam.kind = rt::projection::orthographic;
    cam.fov_degrees.reset();
    const rt::ray_generator ortho = rt::make_ray_generator(cam, 17, 9);
    const rt::vec3 forward = -ortho.basis.w;
    for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 17; ++i) {
            CAPTURE(i);
            CAPTURE(j);
            const rt::ray o = rt::pixel_ray(ortho, i, j);
            {
                INFO("orthographic: expected every direction along -w and every origin on the plane through the eye "
                     "orthogonal to w (origin e + u u + v v), found " << rt_doctest::text(o));
                check_near(glm::normalize(o.direction), forward);
                CHECK(std::fabs(glm::dot(o.origin - cam.eye, ortho.basis.w)) < tol);
            }
            const rt::ray p = rt::pixel_ray(persp, i, j);
            INFO("perspective: expected every ray to start at the eye and look forward (direction . -w > 0), found "
                 << rt_doctest::text(p));
            check_near(p.origin, cam.eye);
            CHECK(glm::dot(p.direction, forward) > 0);
        }
}

TEST_CASE("pixel rays are symmetric about the image centre")
{
    rt::camera cam;
    cam.fov_degrees = 70;
    const rt::ray_generator gen = rt::make_ray_generator(cam, 8, 6);
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 8; ++i) {
            const rt::vec3 a = rt::pixel_ray(gen, i, j).direction;
            const rt::vec3 b = rt::pixel_ray(gen, 7 - i, 5 - j).direction;
            // mirrored across the centre: the u and v components flip, the w component stays
            CAPTURE(i);
            CAPTURE(j);
            INFO("pixel (i, j) and pixel (7 - i, 5 - j) mirror each other across the image centre: expected their "
                 "directions' u and v components opposite and their w components equal, found "
                 << rt_doctest::text(a) << " and " << rt_doctest::text(b));
            CHECK(glm::dot(a, gen.basis.u) == doctest::Approx(-glm::dot(b, gen.basis.u)));
            CHECK(glm::dot(a, gen.basis.v) == doctest::Approx(-glm::dot(b, gen.basis.v)));
            CHECK(glm::dot(a, gen.basis.w) == doctest::Approx(glm::dot(b, gen.basis.w)));
        }
}

TEST_CASE("a default-window camera: fov gives the vertical extent, the image the horizontal one")
{
    rt::camera cam;
    cam.fov_degrees = 90;
    const rt::window w = rt::effective_window(cam, 300, 100);
    INFO("fov 90 over a 300 x 100 image: expected t = tan(45 degrees) = 1 and r = t nx / ny = 3");
    CHECK(w.t == doctest::Approx(1));
    CHECK(w.r == doctest::Approx(3));
    cam.kind = rt::projection::orthographic;
    cam.fov_degrees.reset();
    const rt::window o = rt::effective_window(cam, 300, 100);
    INFO("orthographic without fov: expected the default window t = 1, r = t nx / ny = 3");
    CHECK(o.t == doctest::Approx(1));
    CHECK(o.r == doctest::Approx(3));
}

TEST_CASE("direction to colour maps [-1, 1] to [0, 1] per channel of the unit direction")
{
    INFO("the colour is (d / |d| + 1) / 2: normalise the direction first; (5, 0, 0) is the unit direction (1, 0, 0) "
         "and gives red 1, not (5 + 1) / 2 = 3");
    const rt::color right = rt::direction_to_color({5, 0, 0});
    CHECK(right.r == doctest::Approx(1));
    CHECK(right.g == doctest::Approx(0.5));
    CHECK(right.b == doctest::Approx(0.5));
    const rt::color ahead = rt::direction_to_color({0, 0, -2});
    CHECK(ahead.r == doctest::Approx(0.5));
    CHECK(ahead.b == doctest::Approx(0));
    const rt::color diagonal = rt::direction_to_color({1, 1, 1});
    CHECK(diagonal.g == doctest::Approx(0.5 + 0.5 / std::sqrt(3.0)));
}

TEST_CASE("the ray image's pixels follow the analytic mapping, top row first")
{
    const rt::ray_generator gen = rt::make_ray_generator(looking_down_minus_z(rt::projection::perspective), 4, 2);
    const rt::image img = rt::render_ray_directions(gen);
    REQUIRE_MESSAGE(img.width == 4, "expected the ray image to be as wide as the generator (nx = 4)");
    REQUIRE_MESSAGE(img.height == 2, "expected the ray image to be as tall as the generator (ny = 2)");
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 4; ++i) {
            // by hand: direction (i - 1.5, j - 0.5, -1), colour (d^ + 1) / 2
            const double x = i - 1.5, y = j - 0.5, z = -1;
            const double n = std::sqrt(x * x + y * y + z * z);
            const rt::color c = img.at(i, 1 - j); // row j from the bottom is image row 1 - j
            CAPTURE(i);
            CAPTURE(j);
            INFO("pixel (i, j), j counted from the bottom row, is image row ny - 1 - j (the image is stored top row "
                 "first); its ray has direction d = (i - 1.5, j - 0.5, -1) and its colour is (d / |d| + 1) / 2 = "
                 << rt_doctest::text(rt::vec3(rt::real((x / n + 1) / 2), rt::real((y / n + 1) / 2), rt::real((z / n + 1) / 2))));
            CHECK(c.r == doctest::Approx((x / n + 1) / 2));
            CHECK(c.g == doctest::Approx((y / n + 1) / 2));
            CHECK(c.b == doctest::Approx((z / n + 1) / 2));
        }
}

TEST_CASE("PPM output: P6 header, then width * height * 3 bytes, clamped and gamma-encoded")
{
    rt::image img(3, 2);
    img.at(0, 0) = {1, 0, 0};
    img.at(1, 0) = {2, -1, 0.5f}; // clamped to 1 and 0
    img.at(2, 1) = {0.25f, 0.25f, 0.25f};
    std::ostringstream out;
    rt::write_ppm(out, img, 2.0f);
    const std::string bytes = out.str();
    const std::string header = "P6\n3 2\n255\n";
    INFO("expected the header \"P6\\n3 2\\n255\\n\" (width, then height) and 3 bytes per pixel, top row first, each "
         "round(255 clamp(c, 0, 1)^(1/gamma)), gamma 2 here");
    REQUIRE_MESSAGE(bytes.size() == header.size() + 3 * 2 * 3,
                    "expected " << header.size() + 3 * 2 * 3 << " bytes in all (the header, then 3 x 2 pixels of 3 bytes), found "
                                << bytes.size());
    CHECK(bytes.substr(0, header.size()) == header);
    auto byte = [&](int x, int y, int channel) {
        return int(std::uint8_t(bytes[header.size() + std::size_t((y * 3 + x) * 3 + channel)]));
    };
    CHECK(byte(0, 0, 0) == 255);
    CHECK(byte(0, 0, 1) == 0);
    CHECK(byte(1, 0, 0) == 255);
    CHECK(byte(1, 0, 1) == 0);
    CHECK(byte(1, 0, 2) == 180); // sqrt(0.5) * 255 = 180.3
    CHECK(byte(2, 1, 0) == 128); // sqrt(0.25) * 255 = 127.5, rounded to nearest
}

TEST_CASE("generate_ray on its own: eq. 4.1 from a generator built by hand (no camera frame needed)")
{
    // a tilted frame and an asymmetric window, so every term of eq. 4.1 shows
    rt::ray_generator gen;
    gen.e = rt::vec3(1, 2, 3);
    gen.basis.u = rt::vec3(0, 0, -1);
    gen.basis.v = rt::vec3(0, 1, 0);
    gen.basis.w = rt::vec3(1, 0, 0);
    gen.plane = rt::window{-2, 6, -1, 3};
    gen.d = 2;
    gen.nx = 8;
    gen.ny = 4;
    // pixel (i, j) = (1, 2) at its centre: u = l + (r - l)(i + 0.5)/nx = -2 + 8 * 1.5 / 8 = -0.5,
    // v = b + (t - b)(j + 0.5)/ny = -1 + 4 * 2.5 / 4 = 1.5 (both exact in binary)
    const rt::ray p = rt::generate_ray(gen, 1.5f, 2.5f);
    INFO("the position (1.5, 2.5) in pixels: u = -0.5, v = 1.5 (eq. 4.1); perspective: expected origin e = (1, 2, 3) "
         "and direction -d w + u U + v V = (-2, 1.5, 0.5), found " << rt_doctest::text(p));
    CHECK(p.origin == gen.e);
    // perspective (FCG 4.3.2): d = -d w + u U + v V = (-2, 1.5, 0.5)
    CHECK(p.direction == rt::vec3(-2, 1.5f, 0.5f));
    gen.kind = rt::projection::orthographic;
    const rt::ray o = rt::generate_ray(gen, 1.5f, 2.5f);
    INFO("orthographic: expected origin e + u U + v V = (1, 3.5, 3.5) and direction -w = (-1, 0, 0), found "
         << rt_doctest::text(o));
    // orthographic (FCG 4.3.1): origin e + u U + v V, direction -w
    CHECK(o.origin == rt::vec3(1, 3.5f, 3.5f));
    CHECK(o.direction == rt::vec3(-1, 0, 0));
}
