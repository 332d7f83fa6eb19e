// library_refraction.cpp - refraction.hpp against closed forms: Snell's law,
// the critical angle, a glass slab's parallel shift, the Fresnel reflectance at
// normal incidence, reflectance + transmittance = 1 (with the transmission
// coefficients, computed apart), Schlick's error, Beer's law.
#include "rt_doctest.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include <rt/refraction.hpp>
#include <rt/vec.hpp>

namespace {

const double pi = 3.14159265358979323846;

/// The unit direction at angle theta from -n (n = +z), in the x-z plane.
rt::vec3 incoming(double theta)
{
    return rt::vec3(rt::real(std::sin(theta)), 0, rt::real(-std::cos(theta)));
}

const std::vector<std::pair<rt::real, rt::real>> boundaries = {
    {rt::real(1), rt::real(1.5)}, {rt::real(1.5), rt::real(1)}, {rt::real(1.33), rt::real(1)}, {rt::real(1), rt::real(2.42)}};

} // namespace

TEST_CASE("refract obeys Snell's law: a unit direction in the plane of d and n, eta sin(theta) = eta_t sin(phi)")
{
    const rt::vec3 n(0, 0, 1);
    for (const auto& boundary : boundaries) {
        const rt::real eta = boundary.first, eta_t = boundary.second; // (no structured binding: CAPTURE is a lambda)
        for (int k = 0; k <= 89; ++k) {
            const double theta = k * pi / 180;
            const rt::vec3 d = incoming(theta);
            rt::vec3 t(0);
            if (!rt::refract(d, n, eta, eta_t, t))
                continue; // total internal reflection: the next case checks where it starts
            CAPTURE(eta);
            CAPTURE(eta_t);
            CAPTURE(k);
            CHECK_MESSAGE(std::fabs(double(glm::length(t)) - 1) < 1e-6, "expected a unit direction, found length "
                                                                            << glm::length(t));
            CHECK_MESSAGE(double(t.z) < 0, "expected t to go through the surface (t.n < 0), found t = " << t.z);
            CHECK_MESSAGE(std::fabs(double(t.y)) < 1e-7, "expected t in the plane of d and n, found t.y = " << t.y);
            const double sin_theta = std::sin(theta), sin_phi = double(t.x); // |t| = 1, n = z
            CHECK_MESSAGE(std::fabs(double(eta) * sin_theta - double(eta_t) * sin_phi) < 1e-6,
                          "expected eta sin(theta) = eta_t sin(phi): " << double(eta) * sin_theta << " against "
                                                                       << double(eta_t) * sin_phi);
        }
    }
}

TEST_CASE("total internal reflection starts exactly at the critical angle asin(eta_t / eta)")
{
    const rt::vec3 n(0, 0, 1);
    for (const auto& boundary : boundaries) {
        const rt::real eta = boundary.first, eta_t = boundary.second;
        if (eta <= eta_t)
            continue;
        const double critical = std::asin(double(eta_t) / double(eta));
        CAPTURE(eta);
        CAPTURE(critical);
        rt::vec3 t(0);
        CHECK_MESSAGE(rt::refract(incoming(critical - 1e-3), n, eta, eta_t, t),
                      "expected a refracted ray just below the critical angle");
        CHECK_MESSAGE(std::fabs(double(t.x) - 1) < 0.05, "expected it nearly grazing (sin(phi) near 1), found " << t.x);
        CHECK_MESSAGE(!rt::refract(incoming(critical + 1e-3), n, eta, eta_t, t),
                      "expected total internal reflection just beyond the critical angle");
        CHECK(rt::fresnel_reflectance(rt::real(std::cos(critical + 1e-3)), eta, eta_t) == 1);
        CHECK(rt::schlick_reflectance(rt::real(std::cos(critical + 1e-3)), eta, eta_t) == 1);
        CHECK(rt::fresnel_reflectance(rt::real(std::cos(critical - 1e-3)), eta, eta_t) < 1);
    }
}

TEST_CASE("a ray through a glass slab leaves parallel to itself, shifted by h sin(theta - phi) / cos(phi)")
{
    // the slab 0 <= z <= h of index 1.5 in air; the ray comes down through z = h
    const rt::real h = 2, eta_glass = rt::real(1.5);
    const rt::vec3 up(0, 0, 1);
    for (int degrees : {0, 10, 30, 45, 60, 80}) {
        const double theta = degrees * pi / 180;
        const rt::vec3 d = incoming(theta);
        const rt::vec3 entry(0, 0, h);
        rt::vec3 inside(0), leaving(0);
        REQUIRE(rt::refract(d, up, 1, eta_glass, inside));
        const rt::vec3 exit = entry + inside * (-h / inside.z); // where it reaches z = 0
        REQUIRE(rt::refract(inside, up, eta_glass, 1, leaving)); // the bottom's normal faces the ray: +z
        CAPTURE(degrees);
        CHECK_MESSAGE(glm::length(leaving - d) < 1e-6, "expected the ray to leave parallel to d = " << d << ", found "
                                                                                                   << leaving);
        const double phi = std::asin(std::sin(theta) / double(eta_glass));
        const double shift = double(h) * std::sin(theta - phi) / std::cos(phi); // FCG 4th ed. sec. 13.1, geometry
        const double measured = double(glm::length(glm::cross(exit - entry, d)));  // from the line entry + s d
        CHECK_MESSAGE(std::fabs(measured - shift) <= 1e-5 * std::max(1.0, shift),
                      "expected a lateral shift of " << shift << ", found " << measured);
    }
}

TEST_CASE("Fresnel at normal incidence is ((eta - eta_t) / (eta + eta_t))^2 both ways, and Schlick's R0 agrees")
{
    for (const auto& boundary : boundaries) {
        const rt::real eta = boundary.first, eta_t = boundary.second;
        const double r0 = std::pow((double(eta) - double(eta_t)) / (double(eta) + double(eta_t)), 2);
        CAPTURE(eta);
        CAPTURE(eta_t);
        CHECK(double(rt::fresnel_reflectance(1, eta, eta_t)) == doctest::Approx(r0).epsilon(1e-5));
        CHECK(double(rt::fresnel_reflectance(1, eta_t, eta)) == doctest::Approx(r0).epsilon(1e-5));
        CHECK(double(rt::schlick_reflectance(1, eta, eta_t)) == doctest::Approx(r0).epsilon(1e-5));
    }
    CHECK(double(rt::fresnel_reflectance(1, 1, rt::real(1.5))) == doctest::Approx(0.04).epsilon(1e-5)); // glass: 4 %
}

TEST_CASE("reflectance + transmittance = 1 at every angle (transmission coefficients computed apart)")
{
    // Hecht, Optics, 4th ed., sec. 4.6.2: the amplitude transmission
    // coefficients t_perp = 2 eta cos(theta) / (eta cos(theta) + eta_t cos(phi)),
    // t_par = 2 eta cos(theta) / (eta_t cos(theta) + eta cos(phi)); the power
    // transmitted is (eta_t cos(phi)) / (eta cos(theta)) (t_perp^2 + t_par^2) / 2.
    double worst = 0;
    for (const auto& boundary : boundaries) {
        const rt::real eta = boundary.first, eta_t = boundary.second;
        for (int k = 0; k < 90; ++k) {
            const double theta = k * pi / 180, cos_theta = std::cos(theta);
            const double sin_phi = double(eta) / double(eta_t) * std::sin(theta);
            if (sin_phi >= 1)
                continue;
            const double cos_phi = std::sqrt(1 - sin_phi * sin_phi);
            const double a = double(eta), b = double(eta_t);
            const double t_perp = 2 * a * cos_theta / (a * cos_theta + b * cos_phi);
            const double t_par = 2 * a * cos_theta / (b * cos_theta + a * cos_phi);
            const double T = (b * cos_phi) / (a * cos_theta) * (t_perp * t_perp + t_par * t_par) / 2;
            const double R = double(rt::fresnel_reflectance(rt::real(cos_theta), eta, eta_t));
            worst = std::max(worst, std::fabs(R + T - 1));
        }
    }
    MESSAGE("largest |R + T - 1| over 4 boundaries and 90 angles: " << worst);
    CHECK_MESSAGE(worst < 1e-5, "expected reflectance + transmittance = 1, found an error of " << worst);
}

TEST_CASE("Schlick's approximation stays within 0.05 of the Fresnel equations for glass, both ways")
{
    // Schlick (1994) and FCG 4th ed. sec. 13.1 use it for its speed; its error
    // grows towards grazing angles, largest on the side of the higher index
    for (const auto& boundary : {std::pair<rt::real, rt::real>(1, rt::real(1.5)), {rt::real(1.5), 1}}) {
        const rt::real eta = boundary.first, eta_t = boundary.second;
        double worst = 0, at = 0;
        for (int k = 0; k <= 900; ++k) {
            const double cos_theta = std::cos(k * pi / 1800);
            const double exact = double(rt::fresnel_reflectance(rt::real(cos_theta), eta, eta_t));
            const double approx = double(rt::schlick_reflectance(rt::real(cos_theta), eta, eta_t));
            if (std::fabs(exact - approx) > worst) {
                worst = std::fabs(exact - approx);
                at = k / 10.0;
            }
        }
        MESSAGE("eta " << eta << " -> " << eta_t << ": Schlick's largest error " << worst << " at " << at
                       << " degrees");
        CHECK_MESSAGE(worst < 0.05, "expected Schlick within 0.05 of the exact reflectance, found " << worst);
    }
}

TEST_CASE("Beer's law: nothing lost over no distance, losses over two lengths multiply, exp(-a s) per channel")
{
    const rt::color a(0.1f, 0.5f, 2.0f);
    CHECK(rt::beer_attenuation(a, 0) == rt::color(1));
    const rt::color one = rt::beer_attenuation(a, rt::real(0.7)), two = rt::beer_attenuation(a, rt::real(1.3));
    const rt::color both = rt::beer_attenuation(a, 2);
    CHECK(glm::length(one * two - both) < 1e-6f);
    CHECK(double(both.b) == doctest::Approx(std::exp(-4.0)).epsilon(1e-6));
}
