// Stage 02 - generate rays, and dump them as an image.
//
// Expected values are worked out by hand from Fundamentals of Computer
// Graphics, 4th ed., sec. 4.3 (eq. 4.1 and the two projections); cameras are
// built here, not loaded, so a stage-01 bug cannot fail these cases.
#include "rt_doctest.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <rt/core/byte_level.hpp>
#include <rt/camera/camera.hpp>
#include <rt/output/image_io.hpp>
#include <rt/camera/pixel_sampling.hpp>
#include <rt/core/random.hpp>
#include <rt/camera/ray_image.hpp>

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

/// The film position (x, y), in pixels from the bottom-left corner, that ray r
/// of `gen` went through: the window point u, v it passes (the origin's offset
/// for an orthographic ray, the direction scaled to reach the image plane at
/// distance d for a perspective one) turned back through eq. 4.1.
rt::vec2 film_position(const rt::ray_generator& gen, const rt::ray& r)
{
    rt::vec3 offset = r.origin - gen.e;
    if (gen.kind == rt::projection::perspective)
        offset = (gen.d / -glm::dot(r.direction, gen.basis.w)) * r.direction;
    const double u = double(glm::dot(offset, gen.basis.u)), v = double(glm::dot(offset, gen.basis.v));
    const rt::window& p = gen.plane;
    return rt::vec2(rt::real((u - p.l) / (p.r - p.l) * gen.nx), rt::real((v - p.b) / (p.t - p.b) * gen.ny));
}

/// What a wrong ray says about the mistake, for a case's message: the film
/// position it went through, when it should go through (x, y), and the
/// likeliest cause of that position.
std::string film_hint(const rt::ray_generator& gen, const rt::ray& r, double x, double y)
{
    const rt::vec2 found = film_position(gen, r);
    const double dx = double(found.x) - x, dy = double(found.y) - y;
    if (!std::isfinite(dx) || !std::isfinite(dy))
        return "";
    auto close_to = [](double a, double b) { return std::fabs(a - b) < 1e-3; };
    auto half = [&](double shift) { return close_to(std::fabs(shift), 0.5) || close_to(shift, 0); };
    std::ostringstream out;
    out << "; found the ray through the film position " << rt_doctest::text(found) << " instead of ("
        << x << ", " << y << ")";
    if (half(dx) && half(dy) && !(close_to(dx, 0) && close_to(dy, 0)))
        out << ", half a pixel off: a half-pixel shift. generate_ray(gen, x, y) takes the film position as it is, "
               "u = l + (r - l) x / nx, v = b + (t - b) y / ny; pixel_ray(gen, i, j) already passes the pixel's "
               "centre (i + 0.5, j + 0.5), so adding (or taking away) 0.5 in generate_ray moves every ray by half "
               "a pixel";
    else if (close_to(dx, 0) && close_to(double(found.y), gen.ny - y))
        out << ", (x, ny - y): rows counted from the top; the book counts y from the bottom row, "
               "v = b + (t - b) y / ny";
    return out.str();
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
        CHECK_MESSAGE(std::fabs(glm::dot(f.u, f.v)) < tol, "expected u . v = 0, found " << glm::dot(f.u, f.v));
        CHECK_MESSAGE(std::fabs(glm::dot(f.v, f.w)) < tol, "expected v . w = 0, found " << glm::dot(f.v, f.w));
        CHECK_MESSAGE(std::fabs(glm::dot(f.w, f.u)) < tol, "expected w . u = 0, found " << glm::dot(f.w, f.u));
        check_near(glm::cross(f.u, f.v), f.w); // right-handed
        // w points from the target back to the eye
        const rt::vec3 back = glm::normalize(eyes[k] - targets[k]);
        check_near(f.w, back);
        // v leans towards up: up . v > 0, and up lies in the v-w plane
        INFO("v must lean towards up (up . v > 0): u = up x w, then v = w x u; u = w x up flips u and v, a half turn "
             "of the picture");
        CHECK_MESSAGE(glm::dot(ups[k], f.v) > 0, "expected up . v > 0, found " << glm::dot(ups[k], f.v));
        CHECK_MESSAGE(std::fabs(glm::dot(ups[k], f.u)) < tol,
                      "expected up . u = 0 (up in the v-w plane), found " << glm::dot(ups[k], f.u));
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
    // the field of view not halved shows plainly at fov 60: t = 3 tan(60 degrees)
    const double full = 3 * std::tan(60 * 3.14159265358979323846 / 180);
    const double t60 = double(rt::window_from_fov(60, 3, 64, 64).t);
    const std::string not_halved = std::fabs(t60 - full) < 1e-3 * full
                                       ? "; for fov 60, d = 3 found t = " + std::to_string(t60) +
                                             " = d tan(60 degrees): the field of view not halved (the window's "
                                             "half-height is d tan(fov / 2): in radians fov pi / 360)"
                                       : "";
    INFO("expected t = d tan(fov / 2), b = -t, r = t nx / ny, l = -r (square pixels): fov 90, d = 1, 200 x 100 "
         "gives t = 1, r = 2" << not_halved);
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

TEST_CASE("generate_ray takes the film position as it is: (0, 0) is the window's corner (l, b), (nx, ny) the corner (r, t)")
{
    // Eq. 4.1 with the film position (x, y) itself: u = l + (r - l) x / nx,
    // v = b + (t - b) y / ny. The 4 x 2 image over the window [-2, 2] x [-1, 1]
    // (orthographic, so the ray starts at the window point): (0, 0) is the corner
    // (-2, -1), (4, 2) the corner (2, 1), (1, 0.5) the point (-1, -0.5). The half
    // pixel to a pixel's centre is pixel_ray's (given), not generate_ray's.
    const rt::ray_generator gen = rt::make_ray_generator(looking_down_minus_z(rt::projection::orthographic), 4, 2);
    const struct {
        rt::real x, y;
        rt::vec3 origin;
        const char* what;
    } points[] = {{0, 0, {-2, -1, 0}, "the film's bottom-left corner"},
                  {4, 2, {2, 1, 0}, "the film's top-right corner"},
                  {1, 0.5f, {-1, -0.5f, 0}, "a point inside the film"}};
    for (const auto& point : points) {
        const rt::ray r = rt::generate_ray(gen, point.x, point.y);
        INFO("generate_ray(gen, " << point.x << ", " << point.y << "), " << std::string(point.what)
             << ": expected the ray from " << rt_doctest::text(point.origin)
             << " (u = l + (r - l) x / nx, v = b + (t - b) y / ny, FCG 4th ed., eq. 4.1 and sec. 4.3.1)"
             << film_hint(gen, r, double(point.x), double(point.y)));
        check_near(r.origin, point.origin);
    }
}

TEST_CASE("orthographic rays of pixel (0,0), the centre pixel and the last pixel, by hand")
{
    // 4 x 2 image, window [-2, 2] x [-1, 1]: pixel (i, j) centre is at
    // u = -2 + 4 (i + 0.5) / 4 = i - 1.5,  v = -1 + 2 (j + 0.5) / 2 = j - 0.5.
    const rt::ray_generator gen = rt::make_ray_generator(looking_down_minus_z(rt::projection::orthographic), 4, 2);
    {
        const rt::ray first = rt::pixel_ray(gen, 0, 0);
        INFO("pixel (0, 0) is the bottom-left pixel: x counts columns from the left, y rows from the bottom "
             "(FCG 4th ed., sec. 4.3.1), so its ray starts at u = -1.5, v = -0.5" << film_hint(gen, first, 0.5, 0.5));
        check_near(first.origin, {-1.5, -0.5, 0});
        check_near(first.direction, {0, 0, -1});
    }
    {
        const rt::ray last = rt::pixel_ray(gen, 3, 1);
        INFO("pixel (3, 1) is the top-right pixel (rows counted from the bottom): its ray starts at u = 1.5, v = 0.5"
             << film_hint(gen, last, 3.5, 1.5));
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
             "direction (-1.5, -0.5, -1), not normalised (d = -d w + u u + v v)" << film_hint(gen, first, 0.5, 0.5));
        check_near(first.origin, {0, 0, 0});
        check_near(first.direction, {-1.5, -0.5, -1});
    }
    {
        const rt::ray last = rt::pixel_ray(gen, 3, 1);
        INFO("pixel (3, 1) is the top-right pixel (rows counted from the bottom): its direction is (1.5, 0.5, -1)"
             << film_hint(gen, last, 3.5, 1.5));
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

TEST_CASE("direction to color maps [-1, 1] to [0, 1] per channel of the unit direction")
{
    INFO("the color is (d / |d| + 1) / 2: normalise the direction first; (5, 0, 0) is the unit direction (1, 0, 0) "
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
            // by hand: direction (i - 1.5, j - 0.5, -1), color (d^ + 1) / 2
            const double x = i - 1.5, y = j - 0.5, z = -1;
            const double n = std::sqrt(x * x + y * y + z * z);
            const rt::color c = img.at(i, 1 - j); // row j from the bottom is image row 1 - j
            CAPTURE(i);
            CAPTURE(j);
            INFO("pixel (i, j), j counted from the bottom row, is image row ny - 1 - j (the image is stored top row "
                 "first); its ray has direction d = (i - 1.5, j - 0.5, -1) and its color is (d / |d| + 1) / 2 = "
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
    CHECK_MESSAGE(byte(0, 0, 0) == 255, "pixel (0, 0), the first of the top row: expected red 1 stored as 255");
    CHECK_MESSAGE(byte(0, 0, 1) == 0, "pixel (0, 0): expected green 0 stored as 0");
    CHECK_MESSAGE(byte(1, 0, 0) == 255, "pixel (1, 0): expected red 2, clamped to 1, stored as 255");
    CHECK_MESSAGE(byte(1, 0, 1) == 0, "pixel (1, 0): expected green -1, clamped to 0, stored as 0");
    CHECK_MESSAGE(byte(1, 0, 2) == 180, "pixel (1, 0): expected blue 0.5 stored as round(255 sqrt(0.5)) = "
                                        "round(180.3) = 180"); // sqrt(0.5) * 255 = 180.3
    CHECK_MESSAGE(byte(2, 1, 0) == 128, "pixel (2, 1), the last of the second row: expected red 0.25 stored as "
                                        "round(255 sqrt(0.25)) = round(127.5) = 128 (halves round up)");
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

// ---- sampling: several rays per pixel (include/rt/camera/pixel_sampling.hpp) ----
// Pixel (i, j) is the square [i, i + 1] x [j, j + 1] of film positions; n x n
// jittered samples put one uniform point in each of its n x n cells (FCG 4th
// ed., sec. 13.4.1); the box reconstruction averages the samples inside it.

namespace {

/// The cell (stratum) of a sample inside the pixel, column a or row b in
/// 0 .. n - 1, worked out in double from the float position.
int stratum_of(double position, int pixel, int n)
{
    const double t = (position - pixel) * n; // in [0, n] inside the pixel
    return std::max(0, std::min(int(std::floor(t)), n - 1));
}

/// The generator of one pixel for a seed, as the stage program makes it.
rt::pcg32 generator_for(std::uint64_t seed, int i, int j)
{
    return rt::seeded_generator(seed, std::uint64_t(j) * 1000 + std::uint64_t(i), 0, 1);
}

} // namespace

TEST_CASE("jittered samples: n x n of them, all inside the pixel, exactly one in each cell")
{
    const int pixels[][2] = {{0, 0}, {3, 5}, {17, 2}, {63, 40}};
    for (const int n : {1, 2, 3, 4, 8})
        for (const auto& pixel : pixels)
            for (std::uint64_t seed = 1; seed <= 3; ++seed) {
                const int i = pixel[0], j = pixel[1];
                rt::pcg32 rng = generator_for(seed, i, j);
                const std::vector<rt::vec2> samples = rt::jittered_samples(i, j, n, rng);
                CAPTURE(n);
                CAPTURE(i);
                CAPTURE(j);
                CAPTURE(seed);
                INFO("n x n samples, one per cell: the cell (a, b) holds (i + (a + xi1) / n, j + (b + xi2) / n)");
                REQUIRE(samples.size() == std::size_t(n) * std::size_t(n));
                std::vector<int> per_cell(std::size_t(n) * std::size_t(n), 0);
                for (const rt::vec2& p : samples) {
                    CAPTURE(p);
                    INFO("a sample must lie in the pixel's square [i, i + 1] x [j, j + 1] (film positions, "
                         "pixels from the bottom-left corner)");
                    REQUIRE(p.x >= rt::real(i));
                    REQUIRE(p.x <= rt::real(i + 1));
                    REQUIRE(p.y >= rt::real(j));
                    REQUIRE(p.y <= rt::real(j + 1));
                    const int a = stratum_of(p.x, i, n), b = stratum_of(p.y, j, n);
                    ++per_cell[std::size_t(b * n + a)];
                }
                for (int b = 0; b < n; ++b)
                    for (int a = 0; a < n; ++a) {
                        CAPTURE(a);
                        CAPTURE(b);
                        INFO("each of the n x n cells of the pixel holds exactly one sample");
                        CHECK(per_cell[std::size_t(b * n + a)] == 1);
                    }
            }
}

TEST_CASE("jittered samples: the same generator state gives the same samples, another seed other samples")
{
    for (const int n : {1, 4}) {
        CAPTURE(n);
        rt::pcg32 first = generator_for(7, 2, 3), again = generator_for(7, 2, 3), other = generator_for(8, 2, 3);
        const std::vector<rt::vec2> a = rt::jittered_samples(2, 3, n, first);
        const std::vector<rt::vec2> b = rt::jittered_samples(2, 3, n, again);
        const std::vector<rt::vec2> c = rt::jittered_samples(2, 3, n, other);
        REQUIRE(a.size() == b.size());
        REQUIRE(a.size() == c.size());
        // every sample is checked; the message names how many differ and the first
        std::size_t changed = 0, first_changed = 0, fixed_x = 0, first_fixed_x = 0, fixed_y = 0, first_fixed_y = 0;
        for (std::size_t k = 0; k < a.size(); ++k) {
            if (!(a[k] == b[k]) && changed++ == 0)
                first_changed = k;
            if (!(a[k].x != c[k].x) && fixed_x++ == 0)
                first_fixed_x = k;
            if (!(a[k].y != c[k].y) && fixed_y++ == 0)
                first_fixed_y = k;
        }
        CHECK_MESSAGE(changed == 0, "expected the same samples from the same generator state, found "
                                        << changed << " of " << a.size() << " different, the first: sample " << first_changed << " at "
                                        << a[first_changed] << ", then at " << b[first_changed]
                                        << ": draw every random number from the generator passed in (no rand(), no "
                                           "std::random_device, no generator of your own)");
        INFO("every sample is jittered, x and y: a fixed point in its cell (its centre, its corner) is the same for "
             "every seed");
        CHECK_MESSAGE(fixed_x == 0, "expected every sample's x to change with the seed (7, then 8), found "
                                        << fixed_x << " of " << a.size() << " the same, the first: sample "
                                        << first_fixed_x << " at x = " << a[first_fixed_x].x << " with both seeds");
        CHECK_MESSAGE(fixed_y == 0, "expected every sample's y to change with the seed (7, then 8), found "
                                        << fixed_y << " of " << a.size() << " the same, the first: sample "
                                        << first_fixed_y << " at y = " << a[first_fixed_y].y << " with both seeds");
    }
}

TEST_CASE("jittered samples: every cell draws its own offsets, not one pair reused in all of them")
{
    // One pair (xi1, xi2) drawn once and used in every cell is a regular grid
    // shifted as a whole: uniform in each cell taken alone, so the cases after
    // this one may pass it (it comes first, to name it), but the cells are not independent. Its 64 offsets agree up
    // to float rounding (about 1e-5 here); 64 offsets drawn anew all lie
    // within 0.01 of each other with probability below 64 * 0.01^63, so a
    // spread of 0.01 or less on either axis is the reused pair.
    const int n = 8;
    for (int pixel = 0; pixel < 8; ++pixel) {
        const int i = 3 + pixel, j = 1;
        rt::pcg32 rng = generator_for(17, i, j);
        const std::vector<rt::vec2> samples = rt::jittered_samples(i, j, n, rng);
        REQUIRE(samples.size() == std::size_t(n * n));
        double low[2] = {1, 1}, high[2] = {0, 0};
        for (const rt::vec2& p : samples) {
            const double t[2] = {(p.x - i) * n, (p.y - j) * n};
            for (int k = 0; k < 2; ++k) {
                const double o = t[k] - std::min(std::floor(t[k]), double(n - 1));
                low[k] = std::min(low[k], o);
                high[k] = std::max(high[k], o);
            }
        }
        for (int k = 0; k < 2; ++k)
            CHECK_MESSAGE(high[k] - low[k] > 0.01,
                          "pixel (" << i << ", " << j << "), n = 8: expected the " << (k == 0 ? "x" : "y")
                                    << " offsets of the 64 cells drawn anew in each cell, found them all in ["
                                    << low[k] << ", " << high[k] << "]: one xi" << (k == 0 ? "1" : "2")
                                    << " reused in every cell; draw xi1 and xi2 inside the loop over the cells, "
                                       "once per sample");
        if (!(high[0] - low[0] > 0.01 && high[1] - low[1] > 0.01))
            break; // one pixel says it; the others would repeat it
    }
}

TEST_CASE("jittered samples are uniform in their cells: offsets spread over the whole cell, mean one half")
{
    // 64 pixels x 8 x 8 samples = 4096 offsets (a + xi) n - a = xi, uniform in [0, 1):
    // mean 1/2 with standard deviation sqrt(1/12 / 4096) = 0.0045, so 0.02 is 4.4 deviations
    const int n = 8;
    double sum_x = 0, sum_y = 0, low_x = 1, high_x = 0, low_y = 1, high_y = 0;
    int count = 0;
    for (int pixel = 0; pixel < 64; ++pixel) {
        const int i = pixel % 8, j = pixel / 8;
        rt::pcg32 rng = generator_for(11, i, j);
        for (const rt::vec2& p : rt::jittered_samples(i, j, n, rng)) {
            const double tx = (p.x - i) * n, ty = (p.y - j) * n;
            const double ox = tx - std::min(std::floor(tx), double(n - 1));
            const double oy = ty - std::min(std::floor(ty), double(n - 1));
            sum_x += ox;
            sum_y += oy;
            low_x = std::min(low_x, ox);
            high_x = std::max(high_x, ox);
            low_y = std::min(low_y, oy);
            high_y = std::max(high_y, oy);
            ++count;
        }
    }
    REQUIRE(count == 4096);
    INFO("xi1 and xi2 are uniform in [0, 1): use next_float() as it is, divided by n with the cell index");
    CHECK_MESSAGE(std::fabs(sum_x / count - 0.5) < 0.02, "expected the mean offset of x in its cell, (x - i) n - a, "
                                                         "within 0.02 of 1/2, found " << sum_x / count);
    CHECK_MESSAGE(std::fabs(sum_y / count - 0.5) < 0.02, "expected the mean offset of y in its cell, (y - j) n - b, "
                                                         "within 0.02 of 1/2, found " << sum_y / count);
    CHECK_MESSAGE(low_x < 0.05, "expected offsets of x in the cell down to 0 (the smallest below 0.05), found the "
                                "smallest " << low_x);
    CHECK_MESSAGE(high_x > 0.95, "expected offsets of x in the cell up to 1 (the largest above 0.95), found the "
                                 "largest " << high_x);
    CHECK_MESSAGE(low_y < 0.05, "expected offsets of y in the cell down to 0 (the smallest below 0.05), found the "
                                "smallest " << low_y);
    CHECK_MESSAGE(high_y > 0.95, "expected offsets of y in the cell up to 1 (the largest above 0.95), found the "
                                 "largest " << high_y);
}

TEST_CASE("jittered samples: x and y are jittered independently, so the offsets fill the whole cell, not a line")
{
    // The offsets (x - i) n - a = xi1 and (y - j) n - b = xi2 of 4096 samples (64
    // pixels x 8 x 8), binned into the 4 x 4 squares of side 1/4 of the cell. With
    // xi1 and xi2 independent and uniform each sample lands in a given square with
    // probability 1/16, so a square stays empty with probability (15/16)^4096 =
    // 1.6e-115 and some square with at most 16 times that, 2.5e-114: a correct
    // answer fails with at most that chance, whatever order it draws its numbers
    // in (another order gives other samples from the same seed). The seed is
    // fixed, so a given answer passes or fails every time; the reference passes,
    // and so do the orders xi2 before xi1 and the cells column by column (checked).
    // One random number used for both (xi2 = xi1) puts every offset on the cell's
    // diagonal: 12 squares stay empty (a neighbour of the diagonal may catch a
    // sample where float rounding crosses a square's corner); xi2 = 1 - xi1 the
    // other diagonal, also 12.
    const int n = 8, bins = 4;
    int filled[bins][bins] = {};
    double sum_x = 0, sum_y = 0, sum_xx = 0, sum_yy = 0, sum_xy = 0;
    int count = 0;
    for (int pixel = 0; pixel < 64; ++pixel) {
        const int i = 5 + pixel % 8, j = 2 + pixel / 8;
        rt::pcg32 rng = generator_for(13, i, j);
        for (const rt::vec2& p : rt::jittered_samples(i, j, n, rng)) {
            const double tx = (p.x - i) * n, ty = (p.y - j) * n;
            const double ox = tx - std::min(std::floor(tx), double(n - 1));
            const double oy = ty - std::min(std::floor(ty), double(n - 1));
            const int bx = std::max(0, std::min(int(ox * bins), bins - 1));
            const int by = std::max(0, std::min(int(oy * bins), bins - 1));
            ++filled[by][bx];
            sum_x += ox;
            sum_y += oy;
            sum_xx += ox * ox;
            sum_yy += oy * oy;
            sum_xy += ox * oy;
            ++count;
        }
    }
    REQUIRE(count == 4096);
    int empty = 0, first_bx = 0, first_by = 0;
    for (int by = 0; by < bins; ++by)
        for (int bx = 0; bx < bins; ++bx)
            if (filled[by][bx] == 0 && empty++ == 0) {
                first_bx = bx;
                first_by = by;
            }
    // the sample correlation of the x and y offsets, printed to help: about 0
    // when independent (standard deviation 1/sqrt(4096) = 0.016), 1 on the
    // diagonal, -1 on the other diagonal
    const double cov = sum_xy / count - (sum_x / count) * (sum_y / count);
    const double var_x = sum_xx / count - (sum_x / count) * (sum_x / count);
    const double var_y = sum_yy / count - (sum_y / count) * (sum_y / count);
    const double correlation = var_x > 0 && var_y > 0 ? cov / std::sqrt(var_x * var_y) : 0;
    CHECK_MESSAGE(empty == 0,
                  "expected the samples' offsets in their cells, ((x - i) n - a, (y - j) n - b) = (xi1, xi2), to fill "
                  "every one of the 4 x 4 squares of side 1/4 of the cell, found "
                      << empty << " of the 16 empty (the first: x offsets in [" << first_bx * 0.25 << ", "
                      << (first_bx + 1) * 0.25 << ") with y offsets in [" << first_by * 0.25 << ", "
                      << (first_by + 1) * 0.25 << ")); the x and y offsets have correlation " << correlation
                      << " (about 0 expected): draw xi1 and xi2 separately, two next_float() per sample, one for x "
                         "and one for y (one number for both puts every sample on the cell's diagonal)");
}

TEST_CASE("box reconstruction: the average of a constant is that constant")
{
    rt::pcg32 rng(3, 4); // positions made here, not by the sampler: this case tests the reconstruction alone
    for (const int count : {1, 3, 16, 100}) {
        CAPTURE(count);
        std::vector<rt::vec2> positions;
        for (int k = 0; k < count; ++k) {
            const rt::real x = rt::real(5) + rt::real(rng.next_float());
            const rt::real y = rt::real(2) + rt::real(rng.next_float());
            positions.emplace_back(x, y);
        }
        // dyadic values: every partial sum and the division by a power of two are exact
        const rt::color exact(0.25f, 0.5f, 0.75f);
        const std::vector<rt::color> same(positions.size(), exact);
        const rt::color got = rt::box_reconstruct(5, 2, positions, same);
        INFO("a pixel whose samples all have the same value has that value: divide the sum by the number of samples "
             "inside the pixel");
        CHECK(got.r == doctest::Approx(0.25).epsilon(1e-6));
        CHECK(got.g == doctest::Approx(0.5).epsilon(1e-6));
        CHECK(got.b == doctest::Approx(0.75).epsilon(1e-6));
        const rt::color grey(0.1f, 0.7f, 0.3f);
        const rt::color g = rt::box_reconstruct(5, 2, positions, std::vector<rt::color>(positions.size(), grey));
        CHECK(g.r == doctest::Approx(0.1).epsilon(1e-5));
        CHECK(g.g == doctest::Approx(0.7).epsilon(1e-5));
        CHECK(g.b == doctest::Approx(0.3).epsilon(1e-5));
    }
}

TEST_CASE("box reconstruction of a linear ramp from samples symmetric about the centre is the ramp at the centre")
{
    // L(x, y) = (x / 8, y / 4, (x + y) / 16): the average of a linear function is
    // the function at the average position, and these positions average to the centre.
    auto ramp = [](const rt::vec2& p) { return rt::color(p.x / 8, p.y / 4, (p.x + p.y) / 16); };
    const int i = 3, j = 6;
    const rt::vec2 centre(3.5f, 6.5f);
    const rt::color want = ramp(centre);
    // the centres of the 4 x 4 cells
    std::vector<rt::vec2> grid;
    for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a)
            grid.emplace_back(rt::real(i) + (rt::real(a) + rt::real(0.5)) / 4, rt::real(j) + (rt::real(b) + rt::real(0.5)) / 4);
    // random points and their mirror images through the centre
    rt::pcg32 rng(5, 6);
    std::vector<rt::vec2> pairs;
    for (int k = 0; k < 8; ++k) {
        const rt::real ox = rt::real(rng.next_float()) - rt::real(0.5);
        const rt::real oy = rt::real(rng.next_float()) - rt::real(0.5);
        pairs.emplace_back(centre.x + ox, centre.y + oy);
        pairs.emplace_back(centre.x - ox, centre.y - oy);
    }
    for (const auto* positions : {&grid, &pairs}) {
        std::vector<rt::color> values;
        for (const rt::vec2& p : *positions)
            values.push_back(ramp(p));
        const rt::color got = rt::box_reconstruct(i, j, *positions, values);
        CAPTURE(got);
        CAPTURE(want);
        INFO("every sample inside the pixel counts once, with the same weight (the box filter)");
        CHECK(got.r == doctest::Approx(want.r).epsilon(1e-5));
        CHECK(got.g == doctest::Approx(want.g).epsilon(1e-5));
        CHECK(got.b == doctest::Approx(want.b).epsilon(1e-5));
    }
}

TEST_CASE("box reconstruction: samples outside the pixel count for nothing, and no sample inside gives black")
{
    const int i = 4, j = 1;
    std::vector<rt::vec2> positions = {{4.25f, 1.25f}, {4.75f, 1.75f}};
    std::vector<rt::color> values = {rt::color(0.5f), rt::color(1)};
    // the neighbours' samples, left, right, below, above and diagonal, with a value that would show
    const rt::vec2 outside[] = {{3.5f, 1.5f}, {5.5f, 1.5f}, {4.5f, 0.5f}, {4.5f, 2.5f}, {5.25f, 2.25f}, {-4.5f, -1.5f}};
    for (const rt::vec2& p : outside) {
        positions.push_back(p);
        values.emplace_back(100.0f);
    }
    const rt::color got = rt::box_reconstruct(i, j, positions, values);
    {
        INFO("pixel (4, 1): 2 of the 8 samples are inside it, with the values 0.5 and 1, and 6 outside, with 100: "
             "only the samples in the square [i, i + 1] x [j, j + 1] count, so expected (0.5 + 1) / 2 = 0.75 in each "
             "channel, found "
             << rt_doctest::text(got)
             << std::string(std::fabs(got.r - 1.5f / 8) < 1e-6f // a std::string: doctest prints a char* as a pointer
                                ? ": that is (0.5 + 1) / 8, divided by all 8 samples, not by the 2 inside"
                                : ""));
        CHECK(got.r == doctest::Approx(0.75));
        CHECK(got.g == doctest::Approx(0.75));
        CHECK(got.b == doctest::Approx(0.75));
    }
    const rt::color none = rt::box_reconstruct(7, 7, positions, values);
    INFO("a pixel with no sample inside is black (0, 0, 0), never 0 / 0; found " << rt_doctest::text(none));
    CHECK(none.r == 0);
    CHECK(none.g == 0);
    CHECK(none.b == 0);
}

TEST_CASE("jittered samples with the box on an edge: the covered fraction is off by at most one column of cells")
{
    // the pixel (2, 1) left of the vertical edge x = 2 + c is covered by the fraction c.
    // Stratified: the cells wholly left of the edge count exactly, so only the
    // column the edge crosses is a guess, and the error is at most 1/n.
    const int i = 2, j = 1;
    for (const int n : {1, 2, 4, 8})
        for (const double c : {0.1, 0.3, 0.5, 0.77})
            for (std::uint64_t seed = 1; seed <= 20; ++seed) {
                rt::pcg32 rng = generator_for(seed, i, j);
                const std::vector<rt::vec2> samples = rt::jittered_samples(i, j, n, rng);
                std::vector<rt::color> values;
                for (const rt::vec2& p : samples)
                    values.emplace_back(p.x < i + c ? 1.0f : 0.0f);
                const double estimate = rt::box_reconstruct(i, j, samples, values).r;
                CAPTURE(n);
                CAPTURE(c);
                CAPTURE(seed);
                CAPTURE(estimate);
                CHECK_MESSAGE(std::fabs(estimate - c) <= 1.0 / n + 1e-6,
                              "pixel (2, 1) white left of x = 2 + c and black right of it: expected the box average "
                              "of the n x n jittered samples within 1 / n = " << 1.0 / n << " of c = " << c
                                  << " (only the column of cells the edge crosses is a guess), found " << estimate);
            }
}

TEST_CASE("quantise: every level k/255 comes back as k, halves round up, the rest clamps")
{
    INFO("expected byte = round(255 clamp(v, 0, 1)), halves up: k / 255 gives k, (k + 0.49) / 255 gives k, "
         "(k + 0.51) / 255 gives k + 1; below 0 and NaN give 0, above 1 and inf give 255");
    for (int k = 0; k <= 255; ++k) {
        CAPTURE(k);
        REQUIRE(int(rt::quantize(float(k) / 255)) == k);
        if (k < 255) {
            REQUIRE(int(rt::quantize((float(k) + 0.49f) / 255)) == k);
            REQUIRE(int(rt::quantize((float(k) + 0.51f) / 255)) == k + 1);
        }
    }
    CHECK(int(rt::quantize(0.5f)) == 128); // 127.5 rounds up
    CHECK(int(rt::quantize(-0.1f)) == 0);
    CHECK(int(rt::quantize(1.7f)) == 255);
    CHECK(int(rt::quantize(std::numeric_limits<float>::infinity())) == 255);
    CHECK(int(rt::quantize(std::nanf(""))) == 0);
}

TEST_CASE("to_byte, the early stages' byte: a plain gamma, then quantize")
{
    INFO("to_byte(x, gamma) stores quantize(x^(1/gamma)): 0 and 1 exact, NaN and negatives 0, above 1 255");
    CHECK(int(rt::to_byte(0.0f)) == 0);
    CHECK(int(rt::to_byte(1.0f)) == 255);
    CHECK(int(rt::to_byte(-3.0f)) == 0);
    CHECK(int(rt::to_byte(std::nanf(""))) == 0);
    CHECK(int(rt::to_byte(7.0f)) == 255);
    CHECK(int(rt::to_byte(0.5f, 1.0f)) == 128);
    CHECK(int(rt::to_byte(0.25f, 2.0f)) == 128); // 0.25^(1/2) = 0.5
}
