// library_refraction.cpp - the given part of refraction.hpp against closed
// forms: the exact Fresnel reflectance at normal incidence and past the critical
// angle, reflectance + transmittance = 1 (with the transmission coefficients,
// computed apart), Beer's law. Stage 09's exercises (refract, Schlick) are
// tested in tests/stage09_refraction.cpp.
#include "rt_doctest.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include <rt/shading/refraction.hpp>
#include <rt/core/vec.hpp>

namespace {

const double pi = 3.14159265358979323846;

const std::vector<std::pair<rt::real, rt::real>> boundaries = {
    {rt::real(1), rt::real(1.5)}, {rt::real(1.5), rt::real(1)}, {rt::real(1.33), rt::real(1)}, {rt::real(1), rt::real(2.42)}};

} // namespace

TEST_CASE("the exact reflectance is 1 from the critical angle asin(eta_t / eta) on")
{
    for (const auto& boundary : boundaries) {
        const rt::real eta = boundary.first, eta_t = boundary.second;
        if (eta <= eta_t)
            continue;
        const double critical = std::asin(double(eta_t) / double(eta));
        CAPTURE(eta);
        CAPTURE(critical);
        CHECK(rt::fresnel_reflectance(rt::real(std::cos(critical + 1e-3)), eta, eta_t) == 1);
        CHECK(rt::fresnel_reflectance(rt::real(std::cos(critical - 1e-3)), eta, eta_t) < 1);
        CHECK(rt::refracted_cosine(rt::real(std::cos(critical + 1e-3)), eta, eta_t) == -1);
    }
}

TEST_CASE("Fresnel at normal incidence is ((eta - eta_t) / (eta + eta_t))^2 both ways")
{
    for (const auto& boundary : boundaries) {
        const rt::real eta = boundary.first, eta_t = boundary.second;
        const double r0 = std::pow((double(eta) - double(eta_t)) / (double(eta) + double(eta_t)), 2);
        CAPTURE(eta);
        CAPTURE(eta_t);
        CHECK(double(rt::fresnel_reflectance(1, eta, eta_t)) == doctest::Approx(r0).epsilon(1e-5));
        CHECK(double(rt::fresnel_reflectance(1, eta_t, eta)) == doctest::Approx(r0).epsilon(1e-5));
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

TEST_CASE("Beer's law: nothing lost over no distance, losses over two lengths multiply, exp(-a s) per channel")
{
    const rt::color a(0.1f, 0.5f, 2.0f);
    CHECK(rt::beer_attenuation(a, 0) == rt::color(1));
    const rt::color one = rt::beer_attenuation(a, rt::real(0.7)), two = rt::beer_attenuation(a, rt::real(1.3));
    const rt::color both = rt::beer_attenuation(a, 2);
    CHECK(glm::length(one * two - both) < 1e-6f);
    CHECK(double(both.b) == doctest::Approx(std::exp(-4.0)).epsilon(1e-6));
}
