// library_shading.cpp - the library's shading around the stage-05 exercise:
// shapes without a material are shaded with the default material. No exercise
// is called.
#include "rt_doctest.hpp"
#include "shading_scene.hpp"

#include <cmath>

#include <rt/core/hit_record.hpp>
#include <rt/scene/scene.hpp>
#include <rt/shading/shading.hpp>
#include <rt/intersection/sphere_stable.hpp>

namespace {

using rt_test::always_visible;
using rt_test::one_sphere_scene;
using rt_test::shade_at;
using rt_test::test_material;

void check_color(const rt::color& got, double r, double g, double b, double eps = 1e-5)
{
    CHECK(got.r == doctest::Approx(r).epsilon(eps));
    CHECK(got.g == doctest::Approx(g).epsilon(eps));
    CHECK(got.b == doctest::Approx(b).epsilon(eps));
}

} // namespace

TEST_CASE("the default material shades shapes without a material")
{
    rt::scene s = one_sphere_scene();
    std::get<rt::sphere>(s.shapes[0]).material = -1;
    s.lights.clear();
    const rt::color L = shade_at(s, 0, 0);
    const rt::color expected = s.default_material.ka * s.ambient;
    check_color(L, expected.r, expected.g, expected.b);
}
