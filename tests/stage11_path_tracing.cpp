// Stage 11 - path tracing: cosine-weighted hemisphere sampling, the
// Lambertian estimator, next-event estimation with multiple importance
// sampling, Russian roulette, adaptive sampling (Kajiya 1986; Veach 1997;
// Physically Based Rendering, 4th ed., ch. 2 and 13; CS184 Project 3-1).
//
// A sampling function is judged by its contract: where its directions go,
// how they spread (closed forms, within five standard deviations of a fixed
// pcg32's samples), and what its estimates converge to. The path tracer the
// exercises make is checked on scenes whose answer is known exactly
// (tests/path_scenes.hpp): the white furnace and the inside of a glowing
// enclosure, whose radiance is Le / (1 - rho). Heavier comparisons (the four
// strategies agree on an image, the N^-1/2 law, thread counts) are in
// tests/library_path_tracing.cpp.
#include "rt_doctest.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <rt/bvh/accelerator.hpp>
#include <rt/path_tracing/adaptive.hpp>
#include <rt/path_tracing/emitters.hpp>
#include <rt/path_tracing/hemisphere.hpp>
#include <rt/path_tracing/lambertian.hpp>
#include <rt/path_tracing/mis.hpp>
#include <rt/path_tracing/next_event.hpp>
#include <rt/path_tracing/path_tracer.hpp>
#include <rt/core/random.hpp>
#include <rt/path_tracing/roulette.hpp>

#include "path_scenes.hpp"

namespace {

/// Uniform numbers in [0, 1) from a fixed generator.
struct uniform {
    rt::pcg32 rng{2026, 11};
    rt::real operator()() { return rt::real(rng.next_float()); }
};

using rt_doctest::problems;
using path_scenes::running;

void check_none(const problems& p, const std::string& advice)
{
    INFO(p.count << " bad samples; the first: " << p.first << "; " << advice);
    CHECK(p.count == 0);
}

/// A mean against its exact value: within five standard errors (and a small
/// relative allowance for rounding when the error is 0).
void check_mean(const std::string& what, const running& got, double want, const std::string& hint)
{
    const double allowed = 5 * got.error() + 1e-5 * std::fabs(want);
    INFO("expected " << what << " " << want << " (within 5 standard errors), found " << path_scenes::describe(got)
                     << "; " << (got.error() > 0 ? (got.mean() - want) / got.error() : 0.0) << " standard errors away; "
                     << hint);
    CHECK(std::fabs(got.mean() - want) <= allowed);
}

constexpr double pi = 3.14159265358979323846;

} // namespace

TEST_CASE("cosine_hemisphere: unit directions above the surface, cos(theta) spread as the cosine density says")
{
    // the cosine density: cos^2(theta) is uniform in [0, 1] (Malley's method
    // lifts an even point of the disk, r^2 = sin^2(theta)), so the mean cosine
    // is 2/3 (uniform over the hemisphere: 1/2), and the azimuth is uniform
    uniform u;
    problems off;
    const int total = 20000;
    std::vector<int> bands(10, 0), sectors(8, 0);
    running cosines;
    for (int k = 0; k < total; ++k) {
        const rt::real xi1 = u(), xi2 = u();
        const rt::vec3 w = rt::cosine_hemisphere(xi1, xi2);
        if (std::fabs(double(glm::length(w)) - 1) > 1e-4 || w.z < 0) {
            off.add([&](std::ostream& o) { o << "xi (" << xi1 << ", " << xi2 << ") gave " << rt_doctest::text(w)
                                             << ", of length " << glm::length(w); });
            continue;
        }
        cosines.add(double(w.z));
        ++bands[std::size_t(std::min(9, int(double(w.z * w.z) * 10)))];
        const double phi = std::atan2(double(w.y), double(w.x)) + pi;
        ++sectors[std::size_t(std::min(7, int(phi / (2 * pi) * 8)))];
    }
    check_none(off, "expected unit directions with z >= 0: lift the disk point (x, y) to z = sqrt(1 - x^2 - y^2)");
    check_mean("the mean cos(theta) of cosine-weighted directions", cosines, 2.0 / 3,
               "a mean of 1/2 is the uniform hemisphere: the disk point must be spread evenly over the disk's area "
               "(concentric_disk), then lifted");
    double chi2 = 0;
    for (int b : bands)
        chi2 += (b - total / 10.0) * (b - total / 10.0) / (total / 10.0);
    INFO("expected cos^2(theta) uniform in [0, 1] (10 bands of about " << total / 10 << " each, chi-square below "
         "27.9, p = 0.001), found chi-square " << chi2);
    CHECK(chi2 < 27.9);
    double chi2_phi = 0;
    for (int s : sectors)
        chi2_phi += (s - total / 8.0) * (s - total / 8.0) / (total / 8.0);
    INFO("expected the azimuth uniform (8 sectors, chi-square below 24.3), found chi-square " << chi2_phi);
    CHECK(chi2_phi < 24.3);
}

TEST_CASE("cosine_hemisphere_pdf: cos(theta) / pi, a density over the hemisphere that matches the sampler")
{
    // a density integrates to 1: int p dw = int_0^{pi/2} p(cos t) 2 pi sin t dt
    double total = 0;
    const int steps = 4000;
    for (int k = 0; k < steps; ++k) {
        const double t = (k + 0.5) / steps * pi / 2;
        total += double(rt::cosine_hemisphere_pdf(rt::real(std::cos(t)))) * 2 * pi * std::sin(t) * (pi / 2 / steps);
    }
    {
        INFO("expected the density to integrate to 1 over the hemisphere, found " << total
             << " (cos(theta) / (2 pi) integrates to 1/2; 1 / pi without the cosine to 2)");
        CHECK(total == doctest::Approx(1).epsilon(1e-4));
    }
    {
        // computed before INFO, which doctest evaluates only when it reports
        const double at_normal = double(rt::cosine_hemisphere_pdf(1));
        const double below = double(rt::cosine_hemisphere_pdf(rt::real(-0.5)));
        INFO("expected p = cos(theta) / pi: at the normal 1/pi = " << 1 / pi << ", found " << at_normal
             << "; below the surface 0, found " << below);
        CHECK(at_normal == doctest::Approx(1 / pi).epsilon(1e-5));
        CHECK(below == 0);
    }
    // with the sampler: cos / p is pi for every direction, and the estimate of
    // int cos^2 dw = 2 pi / 3 is right
    uniform u;
    problems off;
    running estimate;
    for (int k = 0; k < 4000; ++k) {
        const rt::real xi1 = u(), xi2 = u();
        const rt::vec3 w = rt::cosine_hemisphere(xi1, xi2);
        const double p = double(rt::cosine_hemisphere_pdf(w.z));
        if (!(p > 0) || std::fabs(double(w.z) / p - pi) > 1e-4 * pi)
            off.add([&](std::ostream& o) { o << "the direction " << rt_doctest::text(w) << " has pdf " << p
                                             << ", so cos / pdf = " << double(w.z) / p; });
        else
            estimate.add(double(w.z * w.z) / p);
    }
    check_none(off, "expected cos(theta) / pdf = pi for every cosine-weighted direction");
    check_mean("the estimate of the integral of cos^2 over the hemisphere, 2 pi / 3,", estimate, 2 * pi / 3,
               "the density must be the sampler's");
}

TEST_CASE("sample_lambertian: directions on the normal's side, spread about it, with the weight f cos / pdf = albedo")
{
    const rt::color albedo(0.5f, 0.25f, 0.8f);
    uniform u;
    problems below, weights, pdfs;
    for (const rt::vec3 n : {rt::vec3(0, 0, 1), rt::vec3(0, 0, -1), glm::normalize(rt::vec3(1, -2, 0.5f)),
                             glm::normalize(rt::vec3(0.001f, 0.002f, -1))}) {
        running along;
        for (int k = 0; k < 3000; ++k) {
            const rt::real xi1 = u(), xi2 = u();
            const rt::bsdf_sample s = rt::sample_lambertian(albedo, n, xi1, xi2);
            const double c = double(glm::dot(s.direction, n));
            if (std::fabs(double(glm::length(s.direction)) - 1) > 1e-4 || c < -1e-6) {
                below.add([&](std::ostream& o) { o << "the normal " << rt_doctest::text(n) << " and xi (" << xi1 << ", "
                                                   << xi2 << ") gave " << rt_doctest::text(s.direction) << ", cos " << c; });
                continue;
            }
            along.add(c);
            if (std::fabs(double(s.pdf) - c / pi) > 1e-4)
                pdfs.add([&](std::ostream& o) { o << "the direction at cos " << c << " about " << rt_doctest::text(n)
                                                  << " has pdf " << s.pdf << ", expected cos / pi = " << c / pi; });
            if (c > 1e-3 && glm::length(s.weight - albedo) > 1e-4f * glm::length(albedo))
                weights.add([&](std::ostream& o) { o << "weight " << rt_doctest::text(s.weight) << " for albedo "
                                                     << rt_doctest::text(albedo); });
        }
        std::ostringstream what;
        what << "the mean cosine between the directions and the normal " << rt_doctest::text(n) << ",";
        check_mean(what.str(), along, 2.0 / 3, "cosine-weighted about n: turn the direction about z onto n (to_world)");
    }
    check_none(below, "expected unit directions on the side of the normal n");
    check_none(pdfs, "expected the pdf of the direction about n, cos(theta) / pi, cos(theta) = direction . n");
    check_none(weights, "expected the weight f cos(theta) / pdf = (albedo / pi) cos / (cos / pi) = the albedo itself; "
                        "albedo / pi is the BRDF alone, without cos / pdf");
}

TEST_CASE("solid_angle_pdf: pdf_A d^2 / |cos|, so that the light sampler's 1 / pdf_w averages to the solid angle of the light")
{
    CHECK(double(rt::solid_angle_pdf(rt::real(0.25), 2, rt::real(0.5))) == doctest::Approx(2));
    CHECK(double(rt::solid_angle_pdf(rt::real(0.25), 2, rt::real(-0.5))) == doctest::Approx(2)); // either side
    CHECK(double(rt::solid_angle_pdf(rt::real(0.25), 2, 0)) == 0);                              // seen edge-on
    // a square light of side 2a at height h above x: its solid angle is
    // 4 asin(a^2 / (a^2 + h^2)); the mean of 1 / pdf_w over points uniform on it
    // (pdf_A = 1 / (2a)^2) estimates it
    const double a = 0.5, h = 1;
    rt::scene s;
    s.materials.push_back(path_scenes::grey(0, 1));
    const auto A = rt::real(a), H = rt::real(h);
    s.shapes.push_back(rt::triangle{rt::vec3(-A, -A, H), rt::vec3(A, -A, H), rt::vec3(A, A, H), 0});
    s.shapes.push_back(rt::triangle{rt::vec3(-A, -A, H), rt::vec3(A, A, H), rt::vec3(-A, A, H), 0});
    const rt::emitter_list lights = rt::find_emitters(s);
    uniform u;
    running omega;
    for (int k = 0; k < 20000; ++k) {
        const rt::real xi0 = u(), xi1 = u(), xi2 = u();
        const rt::emitter_sample y = rt::sample_emitters(lights, xi0, xi1, xi2);
        const rt::real d = glm::length(y.point);
        omega.add(1 / double(rt::solid_angle_pdf(y.pdf_area, d, glm::dot(y.normal, y.point / d))));
    }
    check_mean("the mean of 1 / pdf_w, the square's solid angle,", omega, 4 * std::asin(a * a / (a * a + h * h)),
               "pdf_w = pdf_A d^2 / |cos(theta_y)|: without the cosine the light looks bigger, without d^2 the "
               "units are wrong");
}

TEST_CASE("next_event_estimate: its mean is the light a Lambertian point receives from a glowing square, and 0 from behind either")
{
    // the point below the centre of a square of side 2a at height h, glowing
    // Le: the light it reflects is rho Le F, F the configuration factor of the
    // square, four rectangles a x a with a corner above the point (Howell's
    // catalogue, B-3): F = 4 (1 / (2 pi)) [A / sqrt(1 + A^2) atan(A / sqrt(1 + A^2))
    // + same] with A = a / h
    const double a = 0.5, h = 1, le = 3, rho = 0.6;
    rt::scene s;
    s.materials.push_back(path_scenes::grey(0, float(le)));
    const auto A = rt::real(a), H = rt::real(h);
    // counter-clockwise seen from below: the square glows downwards, towards the point
    s.shapes.push_back(rt::triangle{rt::vec3(-A, -A, H), rt::vec3(A, A, H), rt::vec3(A, -A, H), 0});
    s.shapes.push_back(rt::triangle{rt::vec3(-A, -A, H), rt::vec3(-A, A, H), rt::vec3(A, A, H), 0});
    const rt::emitter_list lights = rt::find_emitters(s);
    const double q = a / h, root = std::sqrt(1 + q * q);
    const double F = 4 * (2 * q / root * std::atan(q / root)) / (2 * pi);
    uniform u;
    running reflected;
    problems behind;
    for (int k = 0; k < 20000; ++k) {
        const rt::real xi0 = u(), xi1 = u(), xi2 = u();
        const rt::emitter_sample y = rt::sample_emitters(lights, xi0, xi1, xi2);
        reflected.add(double(rt::next_event_estimate(rt::color(float(rho)), rt::vec3(0), rt::vec3(0, 0, 1), y).r));
        const rt::color back = rt::next_event_estimate(rt::color(float(rho)), rt::vec3(0), rt::vec3(0, 0, -1), y);
        if (back != rt::color(0.0f))
            behind.add([&](std::ostream& o) { o << "the light point " << rt_doctest::text(y.point) << " behind the surface "
                                                "(normal (0, 0, -1)) gave " << rt_doctest::text(back); });
        const rt::color above = rt::next_event_estimate(rt::color(float(rho)), rt::vec3(0, 0, 2 * H), rt::vec3(0, 0, -1), y);
        if (above != rt::color(0.0f))
            behind.add([&](std::ostream& o) { o << "the point (0, 0, 2) above the light, which glows downwards (y.normal "
                                                << rt_doctest::text(y.normal) << "), got " << rt_doctest::text(above)
                                                << " from " << rt_doctest::text(y.point); });
    }
    check_mean("the light reflected from the square, rho Le F =", reflected, rho * le * F,
               "the estimate is (rho / pi) Le cos(theta_x) / pdf_w with pdf_w = pdf_A d^2 / |cos(theta_y)|");
    check_none(behind, "expected 0 from a light below the surface (cos(theta_x) <= 0) and for a point behind the light "
                       "(y.normal . w >= 0): a triangle glows from its front only");
}

TEST_CASE("power_heuristic: pdf_a^2 / (pdf_a^2 + pdf_b^2), the two weights of a direction adding up to 1")
{
    const double w21 = double(rt::power_heuristic(2, 1)); // before INFO, which is evaluated when it reports
    INFO("expected w(2, 1) = 4 / 5 = 0.8, found " << w21
         << " (2/3 is the balance heuristic pdf_a / (pdf_a + pdf_b), Veach's beta = 1; the power heuristic squares)");
    CHECK(w21 == doctest::Approx(0.8));
    CHECK(double(rt::power_heuristic(1, 1)) == doctest::Approx(0.5));
    CHECK(double(rt::power_heuristic(3, 0)) == doctest::Approx(1));
    CHECK(double(rt::power_heuristic(0, 3)) == doctest::Approx(0));
    CHECK(double(rt::power_heuristic(0, 0)) == 0); // neither strategy can make the direction
    for (const double b : {0.01, 0.3, 1.7, 40.0}) {
        const double sum = double(rt::power_heuristic(rt::real(0.5), rt::real(b)) + rt::power_heuristic(rt::real(b), rt::real(0.5)));
        INFO("expected w(a, b) + w(b, a) = 1 for a = 0.5, b = " << b << ", found " << sum);
        CHECK(sum == doctest::Approx(1).epsilon(1e-5));
    }
}

TEST_CASE("emission_weight and light_sample_weight: the light of an emitter is counted once, whatever the strategy")
{
    using rt::path_strategy;
    const rt::real pdf_bsdf = rt::real(0.4), pdf_light = rt::real(1.3);
    {
        // next-event estimation alone: its shadow ray's light counts fully
        const double nee_aimed = double(rt::light_sample_weight(path_strategy::nee, pdf_light, pdf_bsdf));
        INFO("expected light_sample_weight(nee, ...) = 1 (with nee the shadow ray alone counts a light it can aim at), found " << nee_aimed);
        CHECK(nee_aimed == 1);
    }
    for (const path_strategy kind : {path_strategy::uniform, path_strategy::cosine, path_strategy::nee, path_strategy::mis}) {
        const double hit = double(rt::emission_weight(kind, 2, true, pdf_bsdf, pdf_light));
        const double aimed = rt::samples_lights(kind) ? double(rt::light_sample_weight(kind, pdf_light, pdf_bsdf)) : 0;
        const std::string verdict = hit + aimed > 1.5 ? "the light is counted twice (next-event estimation counted it already)"
                                    : hit + aimed < 0.5 ? "the light is counted by neither" : "the weights must share it";
        INFO("strategy " << std::string(rt::name_of(kind)) << ": a sampled emitter met by the path weighs " << hit
             << ", the shadow ray's estimate of the same light " << aimed << "; expected them to add up to 1: "
             << verdict);
        CHECK(hit + aimed == doctest::Approx(1).epsilon(1e-5));
        // the camera's own view of an emitter and emitters nothing aims at count fully
        const double seen = double(rt::emission_weight(kind, 0, true, pdf_bsdf, pdf_light));
        const double unsampled = double(rt::emission_weight(kind, 3, false, pdf_bsdf, pdf_light));
        INFO("expected weight 1 for the emission the camera ray meets (bounce 0) and for emitters next-event "
             "estimation cannot aim at (a glowing sphere), found " << seen << " and " << unsampled);
        CHECK(seen == 1);
        CHECK(unsampled == 1);
    }
    const double mis_hit = double(rt::emission_weight(path_strategy::mis, 1, true, pdf_bsdf, pdf_light));
    INFO("expected MIS to weigh the path's hit by the power heuristic of (pdf_bsdf, pdf_light) = "
         << 0.16 / (0.16 + 1.69) << ", found " << mis_hit);
    CHECK(mis_hit == doctest::Approx(0.16 / (0.16 + 1.69)).epsilon(1e-4));
}

TEST_CASE("russian_roulette: the path goes on with probability min(1, max throughput), and the mean is unchanged")
{
    uniform u;
    for (const rt::color t : {rt::color(0.5f, 0.2f, 0.1f), rt::color(0.05f), rt::color(0.9f, 0.3f, 0.95f)}) {
        // before the start: always on, unchanged
        {
            rt::color early = t;
            const bool on = rt::russian_roulette(early, 2, 3, rt::real(0.999));
            INFO("expected a path before bounce 3 to go on unchanged, found " << std::string(on ? "on" : "ended")
                 << " with " << rt_doctest::text(early));
            CHECK((on && early == t));
        }
        const int total = 20000;
        running kept;
        int survivors = 0;
        for (int k = 0; k < total; ++k) {
            rt::color now = t;
            const bool goes_on = rt::russian_roulette(now, 3, 3, u());
            survivors += goes_on ? 1 : 0;
            kept.add(goes_on ? double(now.r) : 0.0);
        }
        const double q = double(std::max(t.r, std::max(t.g, t.b)));
        const double share = double(survivors) / total, sigma = std::sqrt(q * (1 - q) / total);
        INFO("throughput " << rt_doctest::text(t) << ": expected a share " << q << " of paths to go on (within "
             << 5 * sigma << "), found " << share);
        CHECK(std::fabs(share - q) <= 5 * sigma + 1e-9);
        std::ostringstream what;
        what << "the mean red throughput after the roulette (unbiased: the survivors divided by q) for " << rt_doctest::text(t) << ",";
        check_mean(what.str(), kept, double(t.r), "a survivor's throughput is divided by the probability q it had to survive");
    }
    rt::color bright(1.5f, 0.2f, 0.2f);
    const bool on = rt::russian_roulette(bright, 5, 3, rt::real(0.999));
    INFO("expected a path whose throughput has a component >= 1 always to go on unchanged, found "
         << std::string(on ? "on" : "ended") << " with " << rt_doctest::text(bright));
    CHECK((on && bright == rt::color(1.5f, 0.2f, 0.2f)));
}

TEST_CASE("pixel_converged: CS184's rule, 1.96 sigma / sqrt(n) <= max_tolerance mu, with the sample standard deviation")
{
    // the samples 1 and 3: mu = 2, sigma^2 = ((1 - 2)^2 + (3 - 2)^2) / (2 - 1) = 2,
    // I = 1.96 sqrt(2) / sqrt(2) = 1.96: converged for a tolerance from 0.98 on
    rt::pixel_statistics two;
    two.add(1);
    two.add(3);
    const bool at_099 = rt::pixel_converged(two, 0.99), at_097 = rt::pixel_converged(two, 0.97);
    INFO("samples 1 and 3: mu = 2, sigma = sqrt(2), I = 1.96; expected converged with max_tolerance 0.99 "
         "(I <= 1.98), found " << std::string(at_099 ? "converged" : "not converged")
         << "; not converged with 0.97 (I > 1.94), found " << std::string(at_097 ? "converged" : "not converged")
         << ". (sigma^2 with n instead of n - 1 gives I = 1.39 and converges at 0.97; the variance for sigma, or "
            "no sqrt(n), gives I = 2.77 and never converges at 0.99)");
    CHECK(at_099);
    CHECK_FALSE(at_097);
    rt::pixel_statistics one, flat, dark;
    one.add(5);
    for (int k = 0; k < 8; ++k) {
        flat.add(0.25);
        dark.add(k == 0 ? 1.0 : 0.0);
    }
    INFO("expected one sample never to converge (its sigma is unknown), eight equal samples to converge (sigma 0), "
         "and one bright sample of eight not to converge at tolerance 0.05");
    CHECK_FALSE(rt::pixel_converged(one, 0.5));
    CHECK(rt::pixel_converged(flat, 0.05));
    CHECK_FALSE(rt::pixel_converged(dark, 0.05));
}

TEST_CASE("the white furnace: a diffuse sphere of albedo 1 in a uniform environment looks exactly like the environment")
{
    // every path from its surface escapes after one bounce with the weight
    // albedo = 1 (cosine sampling): each sample is the environment's radiance
    const rt::scene s = path_scenes::furnace(1, 0.7f);
    const rt::accelerator accel(s);
    const rt::emitter_list lights = rt::find_emitters(s);
    problems off;
    for (const rt::path_strategy kind : {rt::path_strategy::cosine, rt::path_strategy::nee, rt::path_strategy::mis}) {
        rt::path_options o;
        o.strategy = kind;
        for (int k = 0; k < 200; ++k) {
            const rt::ray r{rt::vec3(0, 0, 4), rt::vec3(rt::real(k % 20 - 10) * rt::real(0.02), rt::real(k / 20 - 5) * rt::real(0.04), -1)};
            rt::pcg32 rng = rt::seeded_generator(1, 0, std::uint64_t(k) + 1, rt::integrator_stream);
            const rt::color L = rt::path_radiance(s, accel, lights, r, rng, o);
            if (glm::length(L - rt::color(0.7f)) > 1e-5f)
                off.add([&](std::ostream& o2) { o2 << rt::name_of(kind) << ": the ray " << rt_doctest::text(r) << " brought back "
                                                   << rt_doctest::text(L); });
        }
    }
    check_none(off, "expected every sample to be the environment's radiance (0.7, 0.7, 0.7): a white sphere reflects "
                    "all it receives, and the weight f cos / pdf of a cosine-weighted direction is the albedo, 1");
    // uniform hemisphere sampling: right on average, not sample by sample
    rt::path_options o;
    o.strategy = rt::path_strategy::uniform;
    check_mean("the mean radiance with uniform hemisphere sampling, the environment's", path_scenes::paths_along(s, accel, lights, rt::ray{rt::vec3(0, 0, 4), rt::vec3(0, 0, -1)}, o, 4000, 5),
               0.7, "the weight of a uniform direction is (albedo / pi) cos / (1 / (2 pi)) = 2 albedo cos");
}

TEST_CASE("inside a glowing sphere every ray sees Le / (1 - rho): exactly without roulette, on average with it")
{
    const double le = 0.5;
    for (const float rho : {0.3f, 0.5f, 0.8f}) {
        const rt::scene s = path_scenes::glowing_sphere(rho, float(le));
        const rt::accelerator accel(s);
        const rt::emitter_list lights = rt::find_emitters(s);
        const rt::ray r{rt::vec3(0), glm::normalize(rt::vec3(0.3f, -0.2f, 1))};
        // without roulette, B bounces: Le (1 + rho + ... + rho^B), the same for every path
        rt::path_options fixed;
        fixed.strategy = rt::path_strategy::cosine;
        fixed.roulette = false;
        fixed.max_bounces = 12;
        const running exact = path_scenes::paths_along(s, accel, lights, r, fixed, 50, 7);
        const double truncated = le * (1 - std::pow(double(rho), 13)) / (1 - double(rho));
        {
            INFO("rho " << rho << ", 12 bounces without roulette: expected every path to bring back Le (1 - rho^13) / "
                 "(1 - rho) = " << truncated << ", found the mean " << path_scenes::describe(exact));
            CHECK(exact.mean() == doctest::Approx(truncated).epsilon(1e-4));
            CHECK(exact.error() <= 1e-4 * truncated);
        }
        // with roulette and no practical limit: Le / (1 - rho) on average
        rt::path_options roulette;
        roulette.strategy = rt::path_strategy::cosine;
        roulette.max_bounces = 1000;
        std::ostringstream what;
        what << "rho " << rho << ": the mean radiance with Russian roulette, Le / (1 - rho) =";
        check_mean(what.str(), path_scenes::paths_along(s, accel, lights, r, roulette, 3000, 8), le / (1 - double(rho)),
                   "a survivor's throughput is divided by the probability it had to survive");
    }
}

TEST_CASE("inside a glowing cube of triangles every strategy converges to Le / (1 - rho): next-event estimation counts each light once")
{
    // the cube's faces are emitters that next-event estimation samples: a
    // strategy that also adds the emission its path meets counts the light
    // twice and finds more than Le / (1 - rho)
    const double le = 0.5;
    for (const float rho : {0.4f, 0.7f}) {
        const rt::scene s = path_scenes::glowing_cube(rho, float(le));
        const rt::accelerator accel(s);
        const rt::emitter_list lights = rt::find_emitters(s);
        REQUIRE(lights.triangles.size() == 12);
        const rt::ray r{rt::vec3(rt::real(0.1), rt::real(-0.2), 0), glm::normalize(rt::vec3(0.3f, -0.2f, 1))};
        for (const rt::path_strategy kind : {rt::path_strategy::cosine, rt::path_strategy::nee, rt::path_strategy::mis}) {
            rt::path_options o;
            o.strategy = kind;
            o.max_bounces = 1000;
            std::ostringstream what;
            what << "rho " << rho << ", strategy " << rt::name_of(kind) << ": Le / (1 - rho) =";
            check_mean(what.str(), path_scenes::paths_along(s, accel, lights, r, o, 1500, 9), le / (1 - double(rho)),
                       "with next-event estimation, the emission a later bounce meets was counted by the shadow ray "
                       "already (emission_weight)");
        }
    }
}
