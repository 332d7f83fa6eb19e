// library_scene_loader.cpp - the scene file reader (include/rt/input/scene_loader.hpp)
// around the stage-01 exercise: defaults for what a file leaves out, shapes,
// materials and lights in file order, comments and quoted paths, a missing
// file as a clear error. No exercise is called (these scenes state no camera
// the tests look at, or none at all).
#include "rt_doctest.hpp"

#include <string>
#include <variant>

#include <rt/core/error.hpp>
#include <rt/input/scene_loader.hpp>

namespace {

} // namespace

TEST_CASE("a file states only what it needs: every other setting has its default")
{
    const rt::scene s = rt::load_scene_from_string("# nothing but a sphere\nsphere\n");
    CHECK(s.width == 640);
    CHECK(s.height == 480);
    CHECK(s.samples == 1);
    CHECK(s.max_depth == 5);
    CHECK(s.materials.empty());
    CHECK(s.lights.empty());
    REQUIRE(s.shapes.size() == 1);
    const rt::sphere& ball = std::get<rt::sphere>(s.shapes[0]);
    CHECK(ball.center == rt::vec3(0));
    CHECK(ball.radius == doctest::Approx(1));
    CHECK(ball.material == -1);
    CHECK(&s.material_of(ball.material) == &s.default_material);
}

TEST_CASE("the scene holds exactly the shapes, materials and lights the file declares, in order")
{
    const rt::scene s = rt::load_scene_from_string(
        "material red kd 1 0 0\n"
        "material glass kd 0 0 0 ks 1 1 1 p 100 km 0.5 0.5 0.5\n"
        "sphere center 1 2 3 radius 0.5 material glass\n"
        "triangle 0 0 0  1 0 0  0 1 0 material red\n"
        "light point position 0 5 0 intensity 2 2 2\n"
        "light directional direction 0 -1 0\n"
        "ambient 0.2 0.3 0.4\nbackground 1 1 1\nsamples 16\nmax_depth 3\n");
    REQUIRE(s.materials.size() == 2);
    CHECK(s.materials[0].name == "red");
    CHECK(s.materials[0].ka == rt::color(1, 0, 0)); // ka defaults to kd
    CHECK(s.materials[1].p == doctest::Approx(100));
    CHECK(s.materials[1].km == rt::color(0.5f));
    REQUIRE(s.shapes.size() == 2);
    CHECK(std::get<rt::sphere>(s.shapes[0]).material == 1);
    CHECK(std::get<rt::triangle>(s.shapes[1]).material == 0);
    REQUIRE(s.lights.size() == 2);
    CHECK(s.lights[0].kind == rt::light_kind::point);
    CHECK(s.lights[0].intensity == rt::color(2));
    CHECK(s.lights[1].kind == rt::light_kind::directional);
    CHECK(s.ambient == rt::color(0.2f, 0.3f, 0.4f));
    CHECK(s.background == rt::color(1));
    CHECK(s.samples == 16);
    CHECK(s.max_depth == 3);
}

TEST_CASE("a dielectric: ior and attenuation are read, and its diffuse color defaults to 0 (clear glass)")
{
    const rt::scene s = rt::load_scene_from_string("material glass ior 1.5 attenuation 0.1 0.2 0.3\n"
                                                   "material tinted ior 1.33 kd 0.1 0.2 0.3\n"
                                                   "material matte kd 0.5 0.5 0.5\n");
    REQUIRE(s.materials.size() == 3);
    CHECK(rt::is_dielectric(s.materials[0]));
    CHECK(s.materials[0].ior == doctest::Approx(1.5));
    CHECK(s.materials[0].attenuation == rt::color(0.1f, 0.2f, 0.3f));
    CHECK(s.materials[0].kd == rt::color(0.0f)); // clear glass unless kd is given
    CHECK(s.materials[0].ka == rt::color(0.0f)); // ka = kd
    CHECK(s.materials[1].kd == rt::color(0.1f, 0.2f, 0.3f));
    CHECK(s.materials[1].attenuation == rt::color(0.0f));
    CHECK_FALSE(rt::is_dielectric(s.materials[2]));
    CHECK(s.materials[2].ior == 0);
}

TEST_CASE("a material's emission is read (stage 11), defaults to none, and cannot be negative")
{
    const rt::scene s = rt::load_scene_from_string("material lamp kd 0.78 0.78 0.78 emission 17 12 4\n"
                                                   "material matte kd 0.5 0.5 0.5\n");
    REQUIRE(s.materials.size() == 2);
    CHECK(s.materials[0].emission == rt::color(17, 12, 4));
    CHECK(rt::is_emissive(s.materials[0]));
    CHECK(s.materials[1].emission == rt::color(0.0f));
    CHECK_FALSE(rt::is_emissive(s.materials[1]));
    CHECK_FALSE(rt::is_emissive(s.default_material));
    std::string message = "no error";
    try {
        (void)rt::load_scene_from_string("material m emission 1 -2 1\n", "s.scene");
    } catch (const rt::error& e) {
        message = e.what();
    }
    CHECK(message == "s.scene:1:23: expected a non-negative emission, found -2; colors cannot be negative");
}

TEST_CASE("comments, blank lines, tabs and quoted paths are understood")
{
    const rt::scene s = rt::load_scene_from_string(
        "\n   # a comment line\n\tsphere\tradius 2 # trailing comment\n\nmesh \"cube.obj\"\n", "q.scene",
        RT_TEST_DATA_DIR);
    CHECK(s.shapes.size() == 2);
}

TEST_CASE("a missing or unreadable scene file is a clear error")
{
    try {
        rt::load_scene(RT_TEST_DATA_DIR "/no-such.scene");
        FAIL("expected an error");
    } catch (const rt::error& e) {
        CHECK(std::string(e.what()).find("no such file") != std::string::npos);
    }
    try {
        rt::load_scene(RT_TEST_DATA_DIR);
        FAIL("expected an error");
    } catch (const rt::error& e) {
        CHECK(std::string(e.what()).find("found a folder") != std::string::npos);
    }
}
