// library_obj_check.cpp - the OBJ and MTL loader (include/rt/input/obj_loader.hpp):
// a mesh keeps only what its file gives, faces with negative indices and
// polygons, MTL colors per face, the Cornell box, and malformed or missing
// files as one-line errors with file:line:col. No exercise is called.
#include "rt_doctest.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <rt/bvh/accelerator.hpp>
#include <rt/bvh/bvh.hpp>
#include <rt/input/obj_loader.hpp>
#include <rt/intersection/offset.hpp>
#include <rt/system/path_text.hpp>
#include <rt/intersection/spawn.hpp>
#include <rt/intersection/watertight.hpp>

namespace {

using rt::real;
using rt::vec3;

// --- files written by the OBJ tests ---------------------------------------------

std::filesystem::path scratch_folder(const std::string& name)
{
    const std::filesystem::path folder = std::filesystem::temp_directory_path() / ("rt-stage04-" + name);
    std::filesystem::create_directories(folder);
    return folder;
}

std::filesystem::path write_file(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

std::string load_error(const std::filesystem::path& path, const rt::obj_limits& limits = {})
{
    try {
        rt::load_obj(path, limits);
    } catch (const rt::error& e) {
        return e.what();
    }
    return "no error";
}

bool one_line(const std::string& text)
{
    return text.find('\n') == std::string::npos && text.find('\r') == std::string::npos;
}

} // namespace

TEST_CASE("an OBJ mesh keeps only what its file gives")
{
    const rt::obj_result cube = rt::load_obj(RT_TEST_DATA_DIR "/cube.obj");
    CHECK(cube.geometry.positions.size() == 8);
    CHECK(cube.geometry.triangles.size() == 12); // six quads
    CHECK(cube.polygons == 6);
    CHECK(cube.geometry.normals.empty());
    CHECK(cube.geometry.normal_indices.empty());
    CHECK(cube.geometry.texcoords.empty());
    CHECK(cube.geometry.face_materials.empty());
    CHECK(cube.materials.empty());
    CHECK(cube.geometry.dropped_degenerate == 0);

    const std::filesystem::path folder = scratch_folder("kept");
    // normals and texture coordinates given and used
    rt::obj_result with = rt::load_obj(write_file(folder / "with.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                                        "vn 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                                                        "f 1/1/1 2/2/1 3/3/1\n"));
    CHECK(with.geometry.normals.size() == 1);
    REQUIRE(with.geometry.normal_indices.size() == 1);
    CHECK(with.geometry.normal_indices[0] == rt::index3{0, 0, 0});
    CHECK(with.geometry.texcoords.size() == 3);
    REQUIRE(with.geometry.texcoord_indices.size() == 1);
    CHECK(with.geometry.texcoord_indices[0] == rt::index3{0, 1, 2});
    // given but not used by any face: not kept
    rt::obj_result unused = rt::load_obj(write_file(folder / "unused.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                                            "vn 0 0 1\nvt 0 0\nf 1 2 3\n"));
    CHECK(unused.geometry.normals.empty());
    CHECK(unused.geometry.texcoords.empty());
    // only normals, in the v//vn form
    rt::obj_result normals_only =
        rt::load_obj(write_file(folder / "normals.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n"));
    CHECK(normals_only.geometry.normals.size() == 1);
    CHECK(normals_only.geometry.texcoords.empty());
}

TEST_CASE("OBJ faces: negative indices count back, polygons are triangulated, zero-area triangles are dropped and counted")
{
    const std::filesystem::path folder = scratch_folder("faces");
    // -1 is the latest vertex so far: "f -3 -2 -1" after three v lines is "f 1 2 3"
    rt::obj_result relative = rt::load_obj(write_file(folder / "relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                                                                "f -3 -2 -1\n"
                                                                                "v 0 0 1\nf -4 -3 -1\n"));
    REQUIRE(relative.geometry.triangles.size() == 2);
    CHECK(relative.geometry.triangles[0] == rt::index3{0, 1, 2});
    CHECK(relative.geometry.triangles[1] == rt::index3{0, 1, 3});
    // a quad gives 2 triangles, a (convex) pentagon 3
    rt::obj_result polygons = rt::load_obj(write_file(folder / "polygons.obj", "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
                                                                                "v 3 0.5 0\nf 1 2 3 4\nf 1 2 5 3 4\n"));
    CHECK(polygons.polygons == 2);
    CHECK(polygons.geometry.triangles.size() == 5);
    // a repeated corner and three corners on a line have no area
    rt::obj_result degenerate = rt::load_obj(write_file(folder / "degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
                                                                                    "f 1 2 3\nf 1 1 2\nf 1 2 4\n"));
    CHECK(degenerate.geometry.triangles.size() == 1);
    CHECK(degenerate.geometry.dropped_degenerate == 2);
    CHECK(rt::summary(degenerate).find("2 degenerate triangles dropped") != std::string::npos);
}

TEST_CASE("MTL colors become rt materials, per face")
{
    const std::filesystem::path folder = scratch_folder("mtl");
    write_file(folder / "colors.mtl", "# two materials\n"
                                       "newmtl red\nKa 0.1 0.2 0.3\nKd 0.8 0.1 0.1   # inline comment\n"
                                       "Ks 0.5 0.5 0.5\nNs 64\nillum 2\n"
                                       "newmtl mirror\nKd 0.5\nKs 0.9 0.9 0.9\nillum 3\nKe 1 1 1\nmap_Kd wood.png\n");
    const rt::obj_result loaded = rt::load_obj(write_file(folder / "colored.obj", "mtllib colors.mtl\n"
                                                                                   "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                                                                   "f 1 2 3\nusemtl red\nf 2 4 3\n"
                                                                                   "usemtl mirror\nf 1 2 4\n"));
    REQUIRE(loaded.materials.size() == 2);
    const rt::material& red = loaded.materials[0];
    CHECK(red.name == "red");
    CHECK(red.ka == rt::color(0.1f, 0.2f, 0.3f));
    CHECK(red.kd == rt::color(0.8f, 0.1f, 0.1f));
    CHECK(red.ks == rt::color(0.5f));
    CHECK(red.p == 64);
    CHECK(red.km == rt::color(0.0f)); // illum 2: no reflection
    const rt::material& mirror = loaded.materials[1];
    CHECK(mirror.kd == rt::color(0.5f)); // "Kd r" is r r r
    CHECK(mirror.ka == mirror.kd);       // no Ka: as in scene files
    CHECK(mirror.p == rt::material{}.p); // no Ns: the default exponent
    CHECK(mirror.km == rt::color(0.9f)); // illum 3: reflection on, km = Ks
    CHECK(mirror.emission == rt::color(1.0f)); // Ke: the emitted radiance (stage 11)
    CHECK(red.emission == rt::color(0.0f));    // no Ke: emits nothing
    CHECK(!rt::is_emissive(red));
    CHECK(rt::is_emissive(mirror));
    const rt::mesh& m = loaded.geometry;
    REQUIRE(m.face_materials.size() == 3);
    CHECK(m.face_materials[0] == -1); // before any usemtl: the mesh's own material
    CHECK(m.face_materials[1] == 0);
    CHECK(m.face_materials[2] == 1);
    CHECK(rt::triangle_material(m, 0) == m.material);
    CHECK(rt::triangle_material(m, 2) == 1);
}

TEST_CASE("the Cornell box: negative indices, quads and its MTL file")
{
    const std::filesystem::path cornell = std::filesystem::path(RT_SHARED_DIR) / "meshes" / "CornellBox-Original.obj";
    if (!std::filesystem::exists(cornell)) {
        RT_SKIP(cornell.string() + " is not there (../shared/meshes)");
    }
    const rt::obj_result loaded = rt::load_obj(cornell);
    const rt::mesh& m = loaded.geometry;
    CHECK(m.positions.size() == 72);
    CHECK(m.triangles.size() == 36); // 18 quads
    CHECK(m.dropped_degenerate == 0);
    REQUIRE(loaded.materials.size() == 8);
    // the floor is the first quad, "f -4 -3 -2 -1" after its four vertices:
    // its triangles use vertices 0 to 3 only, and the floor material
    CHECK(m.triangles[0][0] < 4);
    CHECK(m.triangles[1][2] < 4);
    REQUIRE(m.face_materials.size() == 36);
    CHECK(loaded.materials[std::size_t(m.face_materials[0])].name == "floor");
    int emitting = 0;
    for (const rt::material& mat : loaded.materials) {
        if (mat.name == "leftWall")
            CHECK(mat.kd == rt::color(0.63f, 0.065f, 0.05f));
        if (mat.name == "light")
            CHECK(mat.emission == rt::color(17, 12, 4)); // Ke 17 12 4: the box lights itself (stage 11)
        emitting += rt::is_emissive(mat) ? 1 : 0;
    }
    CHECK(emitting == 1); // the others say Ke 0 0 0
}

TEST_CASE("malformed or missing OBJ and MTL files are one-line errors with file:line:col")
{
    const std::filesystem::path folder = scratch_folder("errors");
    write_file(folder / "good.mtl", "newmtl shiny\nKd 1 1 1\n");
    write_file(folder / "bad.mtl", "newmtl a\nKd 1 x 1\n");
    write_file(folder / "early.mtl", "Kd 1 1 1\n");
    struct bad_case {
        const char* name;
        const char* text;
        const char* location; // the message starts with this, after the folder
        const char* words;
    };
    const bad_case cases[] = {
        {"not a number", "v 0 0 0\nv 1 x 0\n", "e.obj:2:5:", "expected a number for the vertex y, found 'x'"},
        {"NaN", "v 0 nan 0\n", "e.obj:1:5:", "finite"},
        {"too few coordinates", "v 0 0\n", "e.obj:1:6:", "expected a number for the vertex z, found the end of the line"},
        {"index 0", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "e.obj:4:3:", "other than 0"},
        {"index past the last vertex", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n", "e.obj:5:7:",
         "a vertex index from 1 to 3, found 9"},
        {"negative index before the first vertex", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "e.obj:4:9:",
         "a relative vertex index from -1 to -3, found -4"},
        {"normal index without normals", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n", "e.obj:4:6:",
         "a normal index from 1 to 0"},
        {"a face of two corners", "v 0 0 0\nv 1 0 0\nf 1 2\n", "e.obj:3:1:", "a face of at least 3 corners, found 2"},
        {"a corner that is not an index", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 three\n", "e.obj:4:7:", "'three'"},
        {"malformed MTL line", "mtllib bad.mtl\n", "bad.mtl:2:6:", "expected a number for Kd g, found 'x'"},
        {"MTL statement before newmtl", "mtllib early.mtl\n", "early.mtl:1:1:", "'newmtl name' before 'Kd'"},
        {"binary bytes", "v 0 0 0\n\x01\x02\x03\n", "e.obj:2:1:", "a byte of value 1"},
    };
    for (const bad_case& c : cases) {
        const std::string case_name = c.name;
        CAPTURE(case_name);
        const std::filesystem::path path = write_file(folder / "e.obj", c.text);
        const std::string message = load_error(path);
        CAPTURE(message);
        const std::string where = rt::detail::utf8_text(folder / c.location); // as rt shows a path
        CHECK(message.rfind(where, 0) == 0);
        CHECK(message.find(c.words) != std::string::npos);
        CHECK(message.find("expected") != std::string::npos);
        CHECK(one_line(message));
    }
    // missing materials: a warning line and the default material, an error with strict (--strict)
    const bad_case strict_cases[] = {
        {"missing material library", "mtllib nowhere.mtl\n", "e.obj:1:8:", "no such file"},
        {"unknown material", "mtllib good.mtl\nusemtl dull\n", "e.obj:2:8:", "known: shiny"},
        {"usemtl without a library", "usemtl shiny\n", "e.obj:1:8:", "found usemtl 'shiny' without one"},
    };
    for (const bad_case& c : strict_cases) {
        const std::string case_name = c.name;
        CAPTURE(case_name);
        const std::filesystem::path path = write_file(folder / "e.obj", c.text);
        std::ostringstream warnings;
        rt::obj_limits limits;
        limits.warnings = &warnings;
        CHECK(load_error(path, limits) == "no error");
        CHECK(warnings.str().rfind(rt::detail::utf8_text(folder / c.location) + " warning: ", 0) == 0);
        limits.strict = true;
        const std::string message = load_error(path, limits);
        CAPTURE(message);
        CHECK(message.rfind(rt::detail::utf8_text(folder / c.location), 0) == 0);
        CHECK(message.find(c.words) != std::string::npos);
        CHECK(one_line(message));
    }
    const std::string missing = load_error(folder / "no-such.obj");
    CHECK(missing.find("no such file") != std::string::npos);
    CHECK(missing.rfind(rt::detail::utf8_text(folder / "no-such.obj"), 0) == 0);
    CHECK(load_error(folder).find("found a folder") != std::string::npos);
}
