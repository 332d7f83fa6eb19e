// Stage 01 - load a scene (the camera must load).
//
// Every case builds its input here, from a string, so nothing of a later stage
// can fail it. Error cases check the whole promise: one line, file:line:col,
// what was expected, what was found.
#include "rt_doctest.hpp"

#include <cstdlib>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include <rt/input/camera_statement.hpp>
#include <rt/camera/camera_text.hpp>
#include <rt/input/scene_loader.hpp>

namespace {

/// The message rt::load_scene_from_string throws for `text`, or "" if it loads.
std::string error_of(const std::string& text)
{
    try {
        rt::load_scene_from_string(text, "bad.scene", RT_TEST_DATA_DIR);
    } catch (const rt::error& e) {
        return e.what();
    }
    return "";
}

bool one_line(const std::string& message) { return message.find('\n') == std::string::npos; }

/// A camera's optional field of view or window in words, for messages.
std::string fov_text(const std::optional<rt::real>& fov)
{
    if (!fov)
        return "no field of view (cam.fov_degrees is empty)";
    std::ostringstream out;
    out << "fov ";
    rt_doctest::put_number(out, *fov);
    return out.str();
}

std::string window_text(const std::optional<rt::window>& plane)
{
    return plane ? rt_doctest::text(*plane) : std::string("no window (cam.plane is empty)");
}

} // namespace

TEST_CASE("a camera line loads every field it states")
{
    const rt::scene s = rt::load_scene_from_string(
        "camera perspective eye 1 2 3 look_at 4 5 6 up 0 0 1 fov 30 focal 2\n");
    INFO("the line 'camera perspective eye 1 2 3 look_at 4 5 6 up 0 0 1 fov 30 focal 2': expected every field as "
         "written (kind perspective, fov 30 degrees, focal distance 2) and no window");
    CHECK(s.cam.kind == rt::projection::perspective);
    CHECK(s.cam.eye == rt::vec3(1, 2, 3));
    CHECK(s.cam.look_at == rt::vec3(4, 5, 6));
    CHECK(s.cam.up == rt::vec3(0, 0, 1));
    REQUIRE_MESSAGE(s.cam.fov_degrees.has_value(),
                    "expected fov 30 from 'fov 30', found " << fov_text(s.cam.fov_degrees)
                                                            << ": store the fov option in cam.fov_degrees");
    CHECK(*s.cam.fov_degrees == doctest::Approx(30));
    CHECK(s.cam.focal_distance == doctest::Approx(2));
    CHECK_FALSE_MESSAGE(s.cam.plane.has_value(),
                        "expected no window (the line has no window option), found " << window_text(s.cam.plane));
}

TEST_CASE("an orthographic camera loads its window")
{
    const rt::scene s = rt::load_scene_from_string(
        "image 200 100\ncamera orthographic eye 0 0 5 look_at 0 0 0 window -2 2 -1 1\n");
    INFO("'image 200 100' and 'camera orthographic ... window -2 2 -1 1': expected an orthographic camera with the "
         "window l = -2, r = 2, b = -1, t = 1 (in that order) and a 200 x 100 image");
    CHECK(s.cam.kind == rt::projection::orthographic);
    REQUIRE_MESSAGE(s.cam.plane.has_value(), "expected the window l = -2, r = 2, b = -1, t = 1 from 'window -2 2 -1 1', "
                                             "found "
                                                 << window_text(s.cam.plane)
                                                 << ": store the window option in cam.plane");
    CHECK(s.cam.plane->l == doctest::Approx(-2));
    CHECK(s.cam.plane->r == doctest::Approx(2));
    CHECK(s.cam.plane->b == doctest::Approx(-1));
    CHECK(s.cam.plane->t == doctest::Approx(1));
    CHECK(s.width == 200);
    CHECK(s.height == 100);
}

TEST_CASE("camera options may come in any order and default when left out")
{
    const rt::scene a = rt::load_scene_from_string("camera perspective up 0 1 0 eye 0 0 9\n");
    INFO("options in any order: 'up 0 1 0 eye 0 0 9' sets the eye; what is left out keeps the default of "
         "rt::camera (look_at the origin, no fov unless given)");
    CHECK(a.cam.eye == rt::vec3(0, 0, 9));
    CHECK(a.cam.look_at == rt::vec3(0, 0, 0));
    const rt::scene b = rt::load_scene_from_string("camera perspective\n");
    CHECK(b.cam.eye == rt::camera{}.eye);
    CHECK_FALSE_MESSAGE(b.cam.fov_degrees.has_value(), "'camera perspective' has no fov option: expected no field of "
                                                       "view (the renderer then uses its default), found "
                                                           << fov_text(b.cam.fov_degrees));
}

TEST_CASE("a mesh path is relative to the scene file and the mesh keeps only what the file has")
{
    const rt::scene s = rt::load_scene_from_string("mesh cube.obj scale 2 translate 1 0 0\n", "data.scene",
                                                   RT_TEST_DATA_DIR);
    REQUIRE(s.shapes.size() == 1);
    const rt::mesh& m = std::get<rt::mesh>(s.shapes[0]);
    INFO("tests/data/cube.obj, a unit cube centred at the origin with 8 corners and six quad faces, no normals and "
         "no texture coordinates, scaled by 2 and moved by (1, 0, 0): expected 8 positions, 12 triangles and the "
         "bounds (0, -1, -1) to (2, 1, 1)");
    CHECK(m.positions.size() == 8);
    CHECK(m.triangles.size() == 12); // six quads, triangulated
    CHECK_MESSAGE(m.normals.empty(), "expected no normals (cube.obj has none), found " << m.normals.size());
    CHECK_MESSAGE(m.texcoords.empty(), "expected no texture coordinates (cube.obj has none), found " << m.texcoords.size());
    const rt::aabb box = rt::scene_bounds(s);
    INFO("scene_bounds of a scene whose only shape is this mesh: "
         << std::string(box.empty() ? "found an empty box, so the mesh was skipped: grow the box by every shape's "
                                      "bounds, meshes included (rt::bounds of an rt::mesh)"
                                    : "expected its bounds"));
    CHECK(box.lo == rt::vec3(0, -1, -1));
    CHECK(box.hi == rt::vec3(2, 1, 1));
}

TEST_CASE("scene bounds enclose every shape and nothing more")
{
    const rt::scene s = rt::load_scene_from_string(
        "sphere center 0 0 0 radius 1\nsphere center 5 0 0 radius 2\ntriangle -3 0 0  0 4 0  0 0 -7\n");
    const rt::aabb box = rt::scene_bounds(s);
    {
        INFO("spheres (0, 0, 0) r 1 and (5, 0, 0) r 2 and the triangle (-3, 0, 0) (0, 4, 0) (0, 0, -7): expected the "
             "smallest box holding them, (-3, -2, -7) to (7, 4, 2)");
        CHECK(box.lo == rt::vec3(-3, -2, -7));
        CHECK(box.hi == rt::vec3(7, 4, 2));
    }
    const rt::aabb none = rt::scene_bounds(rt::scene{});
    CHECK_MESSAGE(none.empty(), "a scene without shapes: expected an empty box (lo > hi, as rt::aabb{} starts), found "
                                    << none << ": start from rt::aabb{} and grow it by each shape's box, so that "
                                               "nothing else is inside");
}

namespace {

/// Why a message starts at another column of the right line: "" when it does
/// not. `location` is "file:line:col:". A column past the expected one is the
/// position taken after the value was read (line.here() moves on as it reads).
std::string position_hint(const std::string& message, const std::string& location)
{
    const std::size_t colon = location.rfind(':', location.size() - 2);
    const std::string line_part = location.substr(0, colon + 1); // "file:line:"
    if (message.rfind(line_part, 0) != 0)
        return "";
    const int expected = std::atoi(location.c_str() + colon + 1), found = std::atoi(message.c_str() + colon + 1);
    if (found <= expected)
        return "";
    return ", found column " + std::to_string(found) + ", past where the value starts: the position taken after "
           "reading the value; keep line.here() from before reading it";
}

} // namespace

TEST_CASE("bad scenes: each is one line with file:line:col, the expectation and what was found")
{
    struct bad_case {
        const char* name;
        const char* text;
        const char* location;
        const char* words;
    };
    const bad_case cases[] = {
        {"unknown keyword, with the nearest known one", "sphere\nspere radius 1\n", "bad.scene:2:1:",
         "did you mean 'sphere'?"},
        {"unknown material, with the nearest declared one", "material red\nsphere material rad\n", "bad.scene:2:17:",
         "did you mean 'red'?"},
        {"missing OBJ file", "mesh no-such-file.obj\n", "bad.scene:1:6:", "no such file"},
        {"too few arguments", "triangle 0 0 0 1 0 0 0 1\n", "bad.scene:1:25:", "found the end of the line"},
        {"too many arguments", "ambient 0.1 0.1 0.1 0.1\n", "bad.scene:1:21:", "expected the end of the line"},
        {"not a number", "sphere radius one\n", "bad.scene:1:15:", "expected a number for radius, found 'one'"},
        {"NaN", "sphere center nan 0 0\n", "bad.scene:1:15:", "finite"},
        {"inf", "light point position 0 inf 0\n", "bad.scene:1:24:", "finite"},
        {"a number beyond float and double", "sphere radius 1e400\n", "bad.scene:1:15:", "within"},
        {"negative radius", "sphere radius -2\n", "bad.scene:1:15:", "expected a positive radius"},
        {"zero image size", "image 0 480\n", "bad.scene:1:7:", "image width between 1 and"},
        {"absurd image size (the pixel limit)", "image 100000 100000\n", "bad.scene:1:7:", "pixels"},
        {"up parallel to the view direction", "camera perspective eye 0 0 5 look_at 0 0 0 up 0 0 2\n",
         "bad.scene:1:47:", "not parallel"},
        {"eye equal to look_at", "camera perspective eye 1 1 1 look_at 1 1 1\n", "bad.scene:1:38:",
         "different from the eye"},
        {"zero-length up vector", "camera perspective up 0 0 0\n", "bad.scene:1:23:", "non-zero up"},
        // the page's rules for the camera (docs/stages/01-load-scene.md), each with its words
        {"field of view 0", "camera perspective fov 0\n", "bad.scene:1:24:", "a field of view between 0 and 180 degrees"},
        {"field of view 180", "camera perspective fov 180\n", "bad.scene:1:24:", "a field of view between 0 and 180 degrees"},
        {"negative field of view", "camera perspective fov -30\n", "bad.scene:1:24:", "a field of view between 0 and 180 degrees"},
        {"fov on an orthographic camera", "camera orthographic fov 60\n", "bad.scene:1:25:", "use window l r b t"},
        {"empty window, l = r", "camera orthographic window 1 1 -1 1\n", "bad.scene:1:28:", "a window with l < r and b < t"},
        {"empty window, b > t", "camera orthographic window -1 1 1 -1\n", "bad.scene:1:28:", "a window with l < r and b < t"},
        {"focal distance 0", "camera perspective focal 0\n", "bad.scene:1:26:", "a positive focal distance"},
        {"negative focal distance", "camera perspective focal -2\n", "bad.scene:1:26:", "a positive focal distance"},
        {"both fov and window", "camera perspective fov 60 window -1 1 -1 1\n", "bad.scene:1:1:", "either fov or window"},
        {"zero-length light direction", "light directional direction 0 0 0\n", "bad.scene:1:29:",
         "non-zero direction"},
        {"a second camera", "camera perspective\ncamera orthographic\n", "bad.scene:2:1:", "one camera"},
        {"unknown camera type, with the nearest", "camera perspektive\n", "bad.scene:1:8:",
         "did you mean 'perspective'?"},
        {"unknown option", "sphere radius 1 color red\n", "bad.scene:1:17:", "an option of 'sphere'"},
        {"negative color", "background 0 -1 0\n", "bad.scene:1:14:", "non-negative"},
        {"duplicate material", "material a\nmaterial a\n", "bad.scene:2:10:", "unique"},
        {"degenerate triangle", "triangle 0 0 0 1 1 1 2 2 2\n", "bad.scene:1:10:", "non-zero area"},
        {"empty file", "# only a comment\n", "bad.scene:1:1:", "at least one statement"},
        {"binary garbage", "sphere\n\x01\x02garbage\n", "bad.scene:2:1:", "plain text"},
    };
    // the two checks that keep the frame finite where a square overflows float
    // (in double these cameras load: 1e20 squared fits)
    const bad_case float_cases[] = {
        {"an eye 1e20 from look_at", "camera perspective eye 0 0 1e20 look_at 0 0 0 up 0 1 0\n", "bad.scene:1:41:",
         "an eye within about 1e19 of look_at"},
        {"an up vector of length 1e20", "camera perspective eye 0 0 5 look_at 0 0 0 up 0 1e20 0\n", "bad.scene:1:47:",
         "an up vector whose squared length fits rt::real"},
    };
    std::vector<bad_case> all(std::begin(cases), std::end(cases));
    if (sizeof(rt::real) == sizeof(float))
        all.insert(all.end(), std::begin(float_cases), std::end(float_cases));
    for (const bad_case& c : all) {
        const std::string name = c.name;
        CAPTURE(name);
        const std::string message = error_of(c.text);
        if (message.empty()) {
            FAIL_CHECK("expected an rt::error (" << std::string(c.words) << ") for " << name
                                                 << ", but the scene loaded: refuse it in the loader");
            continue;
        }
        CAPTURE(message);
        CHECK_MESSAGE(message.rfind(c.location, 0) == 0, "expected the message to start with "
                                                             << std::string(c.location) << position_hint(message, c.location));
        CHECK_MESSAGE(message.find(c.words) != std::string::npos, "expected the words '" << std::string(c.words) << "'");
        CHECK_MESSAGE(message.find("expected") != std::string::npos, "expected the words 'expected ..., found ...'");
        CHECK_MESSAGE(one_line(message), "expected a message of one line");
    }
}

TEST_CASE("a camera written as a statement reads back as the same camera")
{
    // stage08_output --camera and the viewer pass cameras this way
    rt::camera cam;
    cam.eye = rt::vec3(rt::real(0.1), rt::real(1) / rt::real(3), rt::real(-7.25));
    cam.look_at = rt::vec3(rt::real(1e-7), rt::real(2.5), rt::real(-1) / rt::real(7));
    cam.up = rt::vec3(rt::real(0.2), 1, rt::real(0.05));
    cam.fov_degrees = rt::real(37.123456789);
    cam.focal_distance = rt::real(1.75);
    const rt::camera back = rt::parse_camera_statement(rt::camera_statement(cam));
    {
        INFO("the statement '" << rt::camera_statement(cam) << "' read back: expected every field exactly as written, "
             "including the fov, and no window");
        CHECK(back.kind == cam.kind);
        CHECK(back.eye == cam.eye); // exactly, not approximately
        CHECK(back.look_at == cam.look_at);
        CHECK(back.up == cam.up);
        REQUIRE_MESSAGE(back.fov_degrees.has_value(), "expected " << fov_text(cam.fov_degrees) << ", found "
                                                                  << fov_text(back.fov_degrees));
        CHECK(*back.fov_degrees == *cam.fov_degrees);
        CHECK_FALSE_MESSAGE(back.plane.has_value(), "expected no window, found " << window_text(back.plane));
        CHECK(back.focal_distance == cam.focal_distance);
    }

    cam.kind = rt::projection::orthographic;
    cam.fov_degrees.reset();
    cam.plane = rt::window{rt::real(-0.3), rt::real(0.9), rt::real(-1) / rt::real(3), rt::real(0.6)};
    const rt::camera flat = rt::parse_camera_statement(rt::camera_statement(cam));
    INFO("the orthographic statement '" << rt::camera_statement(cam) << "' read back: expected its window exactly");
    CHECK(flat.kind == rt::projection::orthographic);
    REQUIRE_MESSAGE(flat.plane.has_value(), "expected " << window_text(cam.plane) << ", found "
                                                        << window_text(flat.plane));
    CHECK(flat.plane->l == cam.plane->l);
    CHECK(flat.plane->r == cam.plane->r);
    CHECK(flat.plane->b == cam.plane->b);
    CHECK(flat.plane->t == cam.plane->t);
}

TEST_CASE("a bad camera statement is one line whose column counts in the statement's own text")
{
    std::string message;
    try {
        rt::parse_camera_statement("perspective eye 0 0 1 look_at 0 0 1", "--camera");
    } catch (const rt::error& e) {
        message = e.what();
    }
    INFO("'perspective eye 0 0 1 look_at 0 0 1' (the eye on the point it looks at): expected one line starting "
         "'--camera:1:' and saying what was expected, found '" << message << "'");
    CHECK_MESSAGE(one_line(message), "expected one line, found a line break in the message");
    CHECK(message.rfind("--camera:1:", 0) == 0);
    CHECK(message.find("expected") != std::string::npos);
    message.clear();
    try {
        rt::parse_camera_statement("perspective eye 0 0 x", "--camera");
    } catch (const rt::error& e) {
        message = e.what();
    }
    // 'x' is the 21st character of the argument text
    CHECK(message == "--camera:1:21: expected a number for eye z, found 'x'");
}
