// Stage 10 - distribution ray tracing: a random point of an area light, the
// thin-lens ray, glossy reflection (Cook, Porter, Carpenter 1984; Fundamentals
// of Computer Graphics, 4th ed., sec. 13.4).
//
// A sampling function is judged by its contract, never by the numbers it
// returns for given xi: any map that puts its points where the contract says,
// spread as it says, passes. Spreads are checked against closed forms with many
// samples (a fixed pcg32, so every run draws the same numbers) and a margin of
// five standard deviations: a right answer fails less than once in a million
// seeds, and a wrong spread is many deviations away. Each case counts what went
// wrong and checks once, with the first bad sample in the message.
#include "rt_doctest.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <rt/bvh/accelerator.hpp>
#include <rt/scene/area_light.hpp>
#include <rt/camera/camera.hpp> // rt::frame
#include <rt/shading/glossy.hpp>
#include <rt/scene/light.hpp>
#include <rt/scene/light_sample.hpp>
#include <rt/core/random.hpp>
#include <rt/scene/scene.hpp>
#include <rt/camera/thin_lens.hpp>

namespace {

/// Uniform numbers in [0, 1) from a fixed generator.
struct uniform {
    rt::pcg32 rng{2026, 10};
    rt::real operator()() { return rt::real(rng.next_float()); }
};

/// A fraction `got` of n trials against the probability `want`: within five
/// standard deviations sqrt(want (1 - want) / n).
void check_fraction(const std::string& what, double got, double want, int n)
{
    const double sigma = std::sqrt(want * (1 - want) / n);
    INFO("expected " << what << " " << want << " (within 5 sigma = " << 5 * sigma << " for " << n
                     << " samples), found " << got << "; " << (got - want) / sigma << " sigma away");
    CHECK(std::fabs(got - want) <= 5 * sigma);
}

using rt_doctest::problems; // the failures of one kind in a loop, and the first in words

void check_none(const problems& p, const std::string& advice)
{
    INFO(p.count << " bad samples; the first: " << p.first << "; " << advice);
    CHECK(p.count == 0);
}

/// The share of n shadow rays from x to a random point of `source` (sample_light
/// with fresh xi) that nothing in `blockers` stops. The rays are this test's own
/// (any_hit on the segment, ends excluded), so no other stage's exercise runs.
double reach_share(const rt::light& source, const rt::vec3& x, const std::vector<rt::shape>& blockers, int n)
{
    rt::scene s;
    s.shapes = blockers;
    const rt::accelerator accel(s);
    uniform u;
    int reach = 0;
    for (int k = 0; k < n; ++k) {
        const rt::real xi1 = u(), xi2 = u();
        const rt::light_sample sample = rt::sample_light(source, x, false, rt::vec2(xi1, xi2));
        const rt::ray shadow{x, sample.distance * sample.l};
        reach += accel.any_hit(shadow, rt::real(1e-4), rt::real(1) - rt::real(1e-4)) ? 0 : 1;
    }
    return double(reach) / n;
}

/// A tilted camera frame: the axes turned by b about x, then by a about y
/// (an orthonormal u, v, w, so that no axis is special).
rt::frame turned_frame(double a, double b)
{
    const auto ca = rt::real(std::cos(a)), sa = rt::real(std::sin(a));
    const auto cb = rt::real(std::cos(b)), sb = rt::real(std::sin(b));
    rt::frame f;
    f.u = rt::vec3(ca, 0, -sa);
    f.v = rt::vec3(sa * sb, cb, ca * sb);
    f.w = rt::vec3(sa * cb, -sb, ca * cb);
    return f;
}

} // namespace

TEST_CASE("sample_rect_light: every point lies on the parallelogram, spread uniformly over its area (chi-square, 4 x 4 cells)")
{
    // a slanted parallelogram: the edges are neither unit nor perpendicular
    const rt::vec3 c(1, 2, 3), a(2, 0, 1), b(0.5f, 0, 3);
    const rt::vec3 n = glm::normalize(glm::cross(a, b));
    uniform u;
    const int total = 32000;
    std::vector<int> cells(16, 0);
    problems off;
    for (int k = 0; k < total; ++k) {
        const rt::real xi1 = u(), xi2 = u();
        const rt::vec3 y = rt::sample_rect_light(c, a, b, xi1, xi2);
        // y - c = s a + t b + h n: (s, t) in [0, 1]^2 and h = 0 on the light
        const rt::vec3 q = y - c;
        const double h = double(glm::dot(q, n));
        const double aa = double(glm::dot(a, a)), ab = double(glm::dot(a, b)), bb = double(glm::dot(b, b));
        const double qa = double(glm::dot(q, a)), qb = double(glm::dot(q, b)), det = aa * bb - ab * ab;
        const double s = (qa * bb - qb * ab) / det, t = (qb * aa - qa * ab) / det;
        if (std::fabs(h) > 1e-4 || s < -1e-5 || s > 1 + 1e-5 || t < -1e-5 || t > 1 + 1e-5) {
            off.add([&](std::ostream& o) { o << "xi (" << xi1 << ", " << xi2 << ") gave " << rt_doctest::text(y) << ", at s = " << s << ", t = " << t
                           << " along the edges and " << h << " off the plane"; });
            continue;
        }
        ++cells[std::size_t(std::min(3, int(s * 4)) * 4 + std::min(3, int(t * 4)))];
    }
    check_none(off, "expected points c + s a + t b with s, t in [0, 1]");
    double chi2 = 0;
    const double expected = total / 16.0;
    for (int cell : cells)
        chi2 += (cell - expected) * (cell - expected) / expected;
    INFO("expected each of the 16 cells of the parallelogram to get about " << expected << " points (chi-square below "
         "37.7, 15 degrees of freedom, p = 0.001), found chi-square " << chi2 << "; equal areas of [0, 1)^2 must go to equal areas");
    CHECK(chi2 < 37.7);
}

TEST_CASE("sample_sphere_light: points on the cap of the sphere the point sees, uniform in solid angle: a ball or a disc in between hides its closed-form share")
{
    // FCG 13.4.2 with PBR 3rd ed. 14.2.3: seen from x, the light (radius R at
    // distance D) fills a cone cos(theta_max) = sqrt(1 - R^2/D^2); a ball of
    // radius a at distance h on the same axis hides the cone
    // cos(alpha) = sqrt(1 - a^2/h^2). Uniform in solid angle, the share of the
    // samples that reach the light is (cos(alpha) - cos(theta_max)) / (1 - cos(theta_max)).
    // So does a disc of radius a at height h, with cos(alpha) = h / sqrt(h^2 + a^2).
    const double R = 1, D = 5, a = 0.3, h = 2;
    rt::light bulb;
    bulb.kind = rt::light_kind::sphere;
    bulb.position = rt::vec3(0, 0, rt::real(D));
    bulb.radius = rt::real(R);
    const rt::vec3 x(0);
    uniform u;
    problems off;
    for (int k = 0; k < 4000; ++k) {
        const rt::real xi1 = u(), xi2 = u();
        const rt::vec3 y = rt::sample_sphere_light(bulb.position, bulb.radius, x, xi1, xi2);
        const rt::vec3 from_center = y - bulb.position;
        // on the sphere, and on the cap seen from x: (y - c).(x - c) >= R^2
        if (std::fabs(double(glm::length(from_center)) - R) > 1e-4 ||
            double(glm::dot(from_center, x - bulb.position)) < R * R * (1 - 1e-4))
            off.add([&](std::ostream& o) { o << "xi (" << xi1 << ", " << xi2 << ") gave " << rt_doctest::text(y) << ", "
                           << glm::length(from_center) << " from the centre"; });
    }
    check_none(off, "expected points on the sphere, on the part that x can see (the nearest hit of a ray from x)");
    const int total = 40000;
    const double cos_max = std::sqrt(1 - R * R / (D * D)), cos_alpha = std::sqrt(1 - a * a / (h * h));
    check_fraction("the share of shadow rays that reach the light past the ball, uniform in solid angle,",
                   reach_share(bulb, x, {rt::sphere{rt::vec3(0, 0, rt::real(h)), rt::real(a)}}, total),
                   (cos_alpha - cos_max) / (1 - cos_max), total);
    // a disc of radius a at height h instead (crossed where the shadow ray
    // meets the plane z = h): it hides the cone cos(alpha_d) = h / sqrt(h^2 + a^2)
    uniform v;
    int reach = 0;
    for (int k = 0; k < total; ++k) {
        const rt::real xi1 = v(), xi2 = v();
        const rt::vec3 l = rt::sample_light(bulb, x, false, rt::vec2(xi1, xi2)).l;
        const double s = h / double(l.z), across = s * std::hypot(double(l.x), double(l.y));
        reach += across > a ? 1 : 0;
    }
    const double cos_disc = h / std::sqrt(h * h + a * a);
    check_fraction("the share of shadow rays that pass a disc of radius 0.3 at height 2, uniform in solid angle,",
                   double(reach) / total, (cos_disc - cos_max) / (1 - cos_max), total);
}

TEST_CASE("sample_rect_light: an edge above the middle of the light hides exactly half of it (the penumbra's middle)")
{
    // the light: the square [-1, 1]^2 at height 4; an opaque half-plane x < 0
    // at height 2 (a large triangle). From the origin, a shadow ray to (x, y, 4)
    // crosses height 2 at x / 2: it is blocked exactly when x < 0.
    rt::light panel;
    panel.kind = rt::light_kind::rect;
    panel.position = rt::vec3(-1, -1, 4);
    panel.edge1 = rt::vec3(2, 0, 0);
    panel.edge2 = rt::vec3(0, 2, 0);
    const int total = 20000;
    check_fraction("the share of shadow rays that reach the half-hidden light",
                   reach_share(panel, rt::vec3(0), {rt::triangle{rt::vec3(0, -1000, 2), rt::vec3(0, 1000, 2),
                                                                 rt::vec3(-1000, 0, 2)}}, total),
                   0.5, total);
}

TEST_CASE("thin_lens_ray: each ray starts on the lens disk and meets its pinhole ray on the plane in focus")
{
    const rt::vec3 e(1, 2, 3);
    const rt::frame basis = turned_frame(0.4, 0.25);
    const rt::real aperture = rt::real(0.25), focus = 6;
    uniform u;
    problems off_lens, off_focus;
    for (int k = 0; k < 400; ++k) {
        // pinhole rays through a spread of the film (direction -d w + u u + v v)
        // one draw per statement, so that every compiler draws in the same order
        const rt::real across = u() - rt::real(0.5);
        const rt::real up = u() - rt::real(0.5);
        const rt::vec3 d = -basis.w + across * basis.u + up * basis.v;
        const rt::ray pinhole{e, d};
        const rt::real lens1 = u(), lens2 = u();
        const rt::vec2 lens = rt::concentric_disk(lens1, lens2);
        const rt::ray r = rt::thin_lens_ray(pinhole, basis, aperture, focus, lens);
        // where each ray meets the plane in focus: progress `focus` along -w from e
        const rt::vec3 sharp = e + (focus / -glm::dot(d, basis.w)) * d;
        const rt::real along = -glm::dot(r.direction, basis.w);
        const rt::real t = (focus + glm::dot(r.origin - e, basis.w)) / along;
        const rt::vec3 met = r.origin + t * r.direction;
        const rt::vec3 start = r.origin - e;
        const rt::vec3 on_the_lens = e + aperture * (lens.x * basis.u + lens.y * basis.v);
        const bool on_lens = std::fabs(double(glm::dot(start, basis.w))) < 1e-5 &&
                             std::fabs(double(glm::length(start)) - double(aperture * glm::length(lens))) < 1e-5;
        if (!on_lens)
            off_lens.add([&](std::ostream& o) {
                o << "the lens point " << rt_doctest::text(lens) << " gave the ray from " << rt_doctest::text(r.origin);
                if (double(glm::length(start)) < 1e-6 && double(glm::length(lens)) > 1e-3)
                    o << ", the pinhole e itself";
                o << ", expected it to start on the lens at e + aperture (lens.x u + lens.y v) = "
                  << rt_doctest::text(on_the_lens);
            });
        else if (!(along > 0) || double(glm::length(met - sharp)) > 1e-4 * focus)
            off_focus.add([&](std::ostream& o) {
                o << "the lens point " << rt_doctest::text(lens) << " gave the ray from " << rt_doctest::text(r.origin)
                  << " along " << rt_doctest::text(r.direction) << ": it meets the plane in focus at "
                  << rt_doctest::text(met) << " where the pinhole ray meets it at " << rt_doctest::text(sharp);
                // the two ways this goes wrong, named: the pinhole's direction kept, or
                // the point in focus taken at distance focus along d instead of along -w
                const rt::vec3 unit_r = glm::normalize(r.direction), unit_d = glm::normalize(d);
                const rt::vec3 along_d = e + focus * unit_d;
                const rt::vec3 to_along_d = along_d - r.origin;
                if (glm::length(glm::cross(unit_r, unit_d)) < 1e-5f)
                    o << " (the ray keeps the pinhole ray's direction d: aim it at the point in focus instead)";
                else if (glm::length(to_along_d - glm::dot(to_along_d, unit_r) * unit_r) < 1e-4f * focus)
                    o << " (the ray aims at e + focus d / |d|, at distance focus along d: the point in focus is "
                         "where the pinhole ray has gone focus along -w, e + (focus / (-d.w)) d)";
            });
    }
    {
        INFO(off_lens.count << " of 400 rays start off the lens; the first: " << off_lens.first
                            << "; every thin-lens ray starts at a point of the lens disk, not at the pinhole e: a ray "
                               "from e towards the point in focus is the pinhole ray again, and nothing blurs");
        CHECK(off_lens.count == 0);
    }
    check_none(off_focus, "expected the ray from e + aperture (lens.x u + lens.y v) towards the point where the "
                          "pinhole ray meets the plane at distance focus along -w");
}

TEST_CASE("thin_lens_ray: at distance z a point spreads into the circle of confusion, radius aperture |1 - z / focus|")
{
    // by similar triangles: the lens point e + aperture l and the point in
    // focus, followed to depth z, land aperture |l| |1 - z / f| from where the
    // pinhole ray is at that depth
    const rt::frame basis; // u, v, w along x, y, z: the eye looks along -z
    const rt::ray pinhole{rt::vec3(0), rt::vec3(rt::real(0.1), rt::real(-0.05), -1)};
    const rt::real aperture = rt::real(0.2), focus = 4;
    uniform u;
    problems off;
    double widest = 0;
    const std::vector<rt::vec2> rim = {rt::vec2(1, 0), rt::vec2(0, 1), rt::vec2(-1, 0), rt::vec2(0.6f, -0.8f)};
    for (int k = 0; k < 1000; ++k) {
        const rt::real lens1 = u(), lens2 = u();
        const rt::vec2 lens = k < int(rim.size()) ? rim[std::size_t(k)] : rt::concentric_disk(lens1, lens2);
        const rt::ray r = rt::thin_lens_ray(pinhole, basis, aperture, focus, lens);
        for (const double z : {2.0, 8.0}) {
            const double t = (z + double(r.origin.z)) / double(-r.direction.z);
            const rt::vec3 spot = r.origin + rt::real(t) * r.direction - rt::real(z) * pinhole.direction;
            const double want = double(aperture) * std::fabs(1 - z / double(focus)) * double(glm::length(lens));
            widest = std::max(widest, double(glm::length(spot)) / (double(aperture) * std::fabs(1 - z / double(focus))));
            if (std::fabs(double(glm::length(spot)) - want) > 1e-4)
                off.add([&](std::ostream& o) {
                    o << "the lens point " << rt_doctest::text(lens) << " at depth " << z << " lands "
                      << glm::length(spot) << " from the pinhole ray, not " << want;
                    if (double(glm::length(r.origin)) < 1e-6)
                        o << " (the ray starts at the pinhole e = (0, 0, 0), not on the lens, so it follows the "
                             "pinhole ray and never spreads)";
                });
        }
    }
    check_none(off, "expected the circle of confusion aperture |lens| |1 - z / focus|: a sharp plane in focus, blur "
                    "growing with the distance from it");
    INFO("expected the lens's rim (|lens| = 1) to land exactly on the circle of confusion, found the widest spot at "
         << widest << " times its radius aperture |1 - z / focus|");
    CHECK(widest == doctest::Approx(1).epsilon(1e-4));
}

TEST_CASE("glossy_direction: a = 0 is the mirror direction, otherwise unit directions inside the square of side a about r, centred on it")
{
    uniform u;
    problems off;
    // a = 0: the mirror direction itself, for any xi
    for (const rt::vec3 r : {rt::vec3(0, 0, 1), rt::vec3(1, 0, 0), glm::normalize(rt::vec3(0.3f, 1, -0.2f))}) {
        const rt::vec3 g = rt::glossy_direction(r, 0, rt::real(0.3), rt::real(0.9));
        if (glm::length(g - r) > 1e-6)
            off.add([&](std::ostream& o) { o << "a = 0 turned " << rt_doctest::text(r) << " into " << rt_doctest::text(g); });
    }
    check_none(off, "expected a = 0 to give r itself");
    // FCG 13.4.4: r' = r + s u + t v with s, t uniform in [-a/2, a/2], normalised.
    // Followed back to the plane r.x = 1, a direction g is the point g / (g.r);
    // its offset from r is (s, t) in some orthonormal basis of that plane: at
    // most a / sqrt(2) long, with mean 0 and mean square length a^2 / 6.
    const rt::real a = rt::real(0.4);
    for (const rt::vec3 r : {rt::vec3(0, 0, 1), rt::vec3(1, 0, 0), glm::normalize(rt::vec3(-0.3f, 1, -0.2f))}) {
        rt::vec3 sum(0);
        double square = 0;
        const int total = 20000;
        problems wrong;
        for (int k = 0; k < total; ++k) {
            const rt::real xi1 = u(), xi2 = u();
            const rt::vec3 g = rt::glossy_direction(r, a, xi1, xi2);
            const rt::vec3 offset = g / glm::dot(g, r) - r;
            if (std::fabs(double(glm::length(g)) - 1) > 1e-5 || !(glm::dot(g, r) > 0) ||
                double(glm::length(offset)) > double(a) / std::sqrt(2.0) * (1 + 1e-4))
                wrong.add([&](std::ostream& o) { o << "xi (" << xi1 << ", " << xi2 << ") gave " << rt_doctest::text(g) << " about r = "
                                 << rt_doctest::text(r) << ", offset " << glm::length(offset) << " on the plane at r"; });
            sum += offset;
            square += double(glm::dot(offset, offset));
        }
        check_none(wrong, "expected unit directions r + s u + t v normalised, s and t in [-a/2, a/2]");
        // each coordinate has variance a^2 / 12: the mean's length within 5 sigma
        const double sigma = double(a) / std::sqrt(12.0 * total);
        INFO("about r = " << rt_doctest::text(r) << ": expected the offsets centred on r, found their mean at "
                          << glm::length(sum) / total << " (5 sigma per coordinate: " << 5 * sigma << ")");
        CHECK(double(glm::length(sum)) / total < 5 * std::sqrt(2.0) * sigma);
        // |offset|^2 = s^2 + t^2 has mean a^2 / 6 and variance 2 (a^4 / 80 - a^4 / 144)
        const double want = double(a * a) / 6, spread = std::sqrt(2 * (1.0 / 80 - 1.0 / 144)) * double(a * a);
        INFO("expected a mean square offset of a^2 / 6 = " << want << " (the square of side a), found "
                                                           << square / total);
        CHECK(std::fabs(square / total - want) < 5 * spread / std::sqrt(double(total)));
    }
}
