// scene_loader.hpp - read a scene file (stage 01).
//
// The words of a line: scene_statement.hpp. The camera statement, the stage-01
// exercise: camera_statement.hpp.
//
// The format (docs/scene-format.md) is plain text, one statement a line:
//     keyword argument... [option value...]   # comment
// Every statement has documented defaults, so a file states only what it needs.
// Every problem is an rt::error whose message is one line:
//     file:line:col: expected <what>, found <what>; <hint>
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <istream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

#include <glm/geometric.hpp>

#include "camera_model.hpp"
#include "camera_statement.hpp"
#include "error.hpp"
#include "obj_loader.hpp"
#include "path_text.hpp"
#include "scene.hpp"
#include "scene_statement.hpp"
#include "text_file.hpp"

namespace rt {

/// Limits the loader checks before allocating anything, and how to raise them.
struct load_options {
    std::int64_t max_pixels = std::int64_t(1) << 26;  ///< 67 million pixels (8192 x 8192)
    int max_depth = 64;                               ///< the largest max_depth a file may ask for
    int max_samples = 1 << 16;                        ///< the largest samples per pixel
    std::size_t max_line_length = 4096;               ///< characters in one line
    obj_limits obj;                                   ///< limits for the OBJ files a scene names
};

namespace detail {

/// Where a scene file's mesh path leads: relative to the scene file's folder
/// (never to the working directory), or as written when absolute.
inline std::filesystem::path mesh_path(const std::filesystem::path& folder, const std::filesystem::path& written)
{
    return written.is_absolute() ? written : folder / written;
}

/// The folder a scene file's relative paths start from: its parent, or the
/// empty path (the working directory, which messages then leave out) for a
/// scene file named without a folder.
inline std::filesystem::path scene_folder(const std::filesystem::path& scene_file)
{
    return scene_file.parent_path();
}

inline int find_material(const scene& s, statement& line)
{
    const std::string name = line.word("a material name");
    for (std::size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].name == name)
            return int(i);
    std::vector<std::string> known;
    for (const material& m : s.materials)
        known.push_back(m.name);
    throw parse_error(line.last(), "a declared material", "unknown material " + found_text(name),
                      nearest_hint(name, known) + " (declare materials before using them)");
}

inline const std::vector<std::string>& keywords()
{
    static const std::vector<std::string> words = {"image",   "camera",     "material", "sphere",  "triangle",
                                                   "mesh",    "light",      "ambient",  "background",
                                                   "samples", "max_depth",  "lens"};
    return words;
}

/// Reads the statements of a scene file, one at a time, into a scene.
class scene_reader {
public:
    scene_reader(std::string file, std::filesystem::path folder, const load_options& options)
        : file_(std::move(file)), folder_(std::move(folder)), options_(options) {}

    void read_line(const std::string& text, int number)
    {
        const source_location where{file_, number, 1};
        if (text.size() > options_.max_line_length)
            throw parse_error(where, "a line of at most " + std::to_string(options_.max_line_length) + " characters",
                              "a longer one", "the limit is load_options::max_line_length; raise it if you mean it");
        std::vector<token> tokens = tokenize(text, where);
        if (tokens.empty())
            return;
        statement line(file_, number, std::move(tokens), int(text.size()) + 1);
        ++statements_;
        dispatch(line);
        line.end();
    }

    scene finish(int lines)
    {
        if (statements_ == 0)
            throw parse_error({file_, std::max(lines, 1), 1}, "at least one statement", "an empty file",
                              "see docs/scene-format.md for an example scene");
        if (lens_at_) {
            if (result_.cam.kind != projection::perspective && result_.lens.aperture > 0)
                throw parse_error(*lens_at_, "a lens in front of a perspective camera", "an orthographic camera",
                                  "a thin lens focuses a perspective camera's rays; "
                                  "use aperture 0 or a perspective camera");
            if (!focus_given_) // in focus where the camera looks
                result_.lens.focus = glm::length(result_.cam.look_at - result_.cam.eye);
        }
        return std::move(result_);
    }

private:
    void dispatch(statement& line)
    {
        const std::string& keyword = line.keyword();
        if (keyword == "image")
            read_image(line);
        else if (keyword == "camera") {
            if (seen_camera_)
                throw parse_error(line.line_start(), "one camera", "a second camera statement",
                                  "a scene has exactly one camera; delete one");
            seen_camera_ = true;
            parse_camera(line, result_.cam);
        } else if (keyword == "material")
            read_material(line);
        else if (keyword == "sphere")
            read_sphere(line);
        else if (keyword == "triangle")
            read_triangle(line);
        else if (keyword == "mesh")
            read_mesh(line);
        else if (keyword == "light")
            read_light(line);
        else if (keyword == "ambient")
            result_.ambient = line.rgb("ambient intensity");
        else if (keyword == "background")
            result_.background = line.rgb("background colour");
        else if (keyword == "samples")
            result_.samples = line.integer("samples per pixel", 1, options_.max_samples,
                                           "the limit is load_options::max_samples; raise it if you mean it");
        else if (keyword == "lens")
            read_lens(line);
        else if (keyword == "max_depth")
            result_.max_depth = line.integer("max_depth", 0, options_.max_depth,
                                             "the limit is load_options::max_depth; raise it if you mean it");
        else
            throw parse_error(line.line_start(), "a keyword", found_text(keyword), nearest_hint(keyword, keywords()));
    }

    void read_image(statement& line)
    {
        if (seen_image_)
            throw parse_error(line.line_start(), "one image statement", "a second one", "delete one of them");
        seen_image_ = true;
        const source_location where = line.here();
        const int width = line.integer("image width", 1, 1 << 20);
        const int height = line.integer("image height", 1, 1 << 20);
        if (std::int64_t(width) * height > options_.max_pixels)
            throw parse_error(where, "at most " + std::to_string(options_.max_pixels) + " pixels",
                              std::to_string(width) + "x" + std::to_string(height),
                              "raise load_options::max_pixels if you mean it");
        result_.width = width;
        result_.height = height;
    }

    void read_material(statement& line)
    {
        material m;
        m.name = line.word("a material name");
        for (const material& other : result_.materials)
            if (other.name == m.name)
                throw parse_error(line.last(), "a new material name", "a second material " + found_text(m.name),
                                  "material names must be unique");
        bool ambient_given = false, diffuse_given = false;
        source_location km_at{}, attenuation_at{}, glossy_at{};
        bool km_given = false, attenuation_given = false, glossy_given = false;
        line.options({"ka", "kd", "ks", "p", "km", "ior", "attenuation", "glossy", "emission"},
                     [&](const std::string& option) {
            if (option == "ka") {
                m.ka = line.rgb("ka");
                ambient_given = true;
            } else if (option == "kd") {
                m.kd = line.rgb("kd");
                diffuse_given = true;
            } else if (option == "ks")
                m.ks = line.rgb("ks");
            else if (option == "km") {
                km_at = line.last();
                km_given = true;
                m.km = line.rgb("km");
            } else if (option == "ior") {
                const source_location where = line.here();
                m.ior = line.number("the index of refraction ior");
                if (!(m.ior >= 1 && m.ior <= 10))
                    throw parse_error(where, "an index of refraction from 1 to 10", detail::short_number(double(m.ior)),
                                      "glass is 1.5, water 1.33, diamond 2.42");
            } else if (option == "glossy") {
                glossy_at = line.last();
                glossy_given = true;
                const source_location where = line.here();
                m.glossy = line.number("the glossy blur a");
                if (!(m.glossy >= 0 && m.glossy <= 4))
                    throw parse_error(where, "a glossy blur from 0 to 4", detail::short_number(double(m.glossy)),
                                      "it is the side of the square of perturbed directions: 0.1 is brushed metal");
            } else if (option == "emission") {
                m.emission = line.rgb("emission");
            } else if (option == "attenuation") {
                attenuation_at = line.last();
                attenuation_given = true;
                m.attenuation = line.rgb("attenuation");
            } else {
                const source_location where = line.here();
                m.p = line.number("Phong exponent p");
                if (m.p < 0)
                    throw parse_error(where, "a non-negative Phong exponent", detail::short_number(double(m.p)));
            }
        });
        if (is_dielectric(m) && km_given)
            throw parse_error(km_at, "either km (a mirror) or ior (a dielectric)", "both",
                              "a dielectric reflects by the Fresnel equations: drop km");
        if (!is_dielectric(m) && attenuation_given)
            throw parse_error(attenuation_at, "attenuation only with ior", "attenuation without ior",
                              "attenuation is absorption inside a dielectric: add ior (glass 1.5)");
        if (glossy_given && !(m.km.r > 0 || m.km.g > 0 || m.km.b > 0))
            throw parse_error(glossy_at, "glossy only with km", "glossy without a mirror",
                              "glossy blurs a mirror's reflection: add km (0.8 0.8 0.8)");
        if (is_dielectric(m) && !diffuse_given)
            m.kd = color(0.0f); // clear glass unless the file says otherwise
        if (!ambient_given)
            m.ka = m.kd;
        result_.materials.push_back(m);
    }

    void read_sphere(statement& line)
    {
        sphere s;
        line.options({"center", "radius", "material"}, [&](const std::string& option) {
            if (option == "center")
                s.center = line.vector("center");
            else if (option == "radius") {
                const source_location where = line.here();
                s.radius = line.number("radius");
                if (!(s.radius > 0))
                    throw parse_error(where, "a positive radius", std::to_string(s.radius),
                                      "a sphere's radius is its size, not a direction");
            } else
                s.material = find_material(result_, line);
        });
        if (!sphere_fits_its_position(s)) // sphere_shape.hpp
            throw parse_error(line.here(), sphere_radius_expected(s), sphere_radius_found(s), sphere_scale_hint);
        result_.shapes.emplace_back(s);
    }

    void read_triangle(statement& line)
    {
        const source_location where = line.here();
        triangle tri;
        vec3* corners[3] = {&tri.a, &tri.b, &tri.c};
        for (int k = 0; k < 3; ++k) {
            const source_location at = line.here();
            *corners[k] = line.vector(std::string("corner ") + "abc"[k]);
            // the OBJ reader's limit: beyond it the triangle tests' products
            // overflow float and every ray misses the triangle
            const vec3& p = *corners[k];
            const real largest = std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
            if (!(double(largest) <= options_.obj.max_coordinate))
                throw parse_error(at, std::string("a corner ") + "abc"[k] + " within +-" +
                                          detail::short_number(options_.obj.max_coordinate),
                                  "a coordinate of " + detail::short_number(double(largest)),
                                  "float arithmetic cannot trace coordinates that large; use smaller units");
        }
        if (triangle_normal(tri.a, tri.b, tri.c) == vec3(0)) // the library's normal (triangle_shape.hpp)
            throw parse_error(where, "a triangle with non-zero area", "three corners on one line",
                              "check the corners");
        line.options({"material"}, [&](const std::string&) { tri.material = find_material(result_, line); });
        result_.shapes.emplace_back(tri);
    }

    void read_mesh(statement& line)
    {
        const source_location where = line.here();
        const std::filesystem::path relative = utf8_path(line.word("an OBJ file path"));
        int material_index = -2; // -2: keep the materials of the OBJ's MTL file
        real scale = 1;
        vec3 translate(0);
        line.options({"material", "scale", "translate"}, [&](const std::string& option) {
            if (option == "material")
                material_index = find_material(result_, line);
            else if (option == "scale") {
                const source_location at = line.here();
                scale = line.number("scale");
                if (!(scale > 0))
                    throw parse_error(at, "a positive scale", std::to_string(scale));
            } else
                translate = line.vector("translate");
        });
        const std::filesystem::path path = mesh_path(folder_, relative);
        obj_limits limits = options_.obj; // one budget of triangles for all the scene's meshes
        limits.max_triangles -= triangles_;
        obj_result loaded;
        try {
            loaded = load_obj(path, limits);
        } catch (const error& e) {
            throw parse_error(where, "a loadable OBJ mesh", "an error", e.what());
        }
        mesh& m = loaded.geometry;
        if (m.triangles.empty())
            throw parse_error(where, "a mesh with at least one triangle",
                              m.dropped_degenerate > 0 ? "only " + std::to_string(m.dropped_degenerate) +
                                                             " degenerate (zero-area) triangle(s)"
                                                       : "no faces",
                              "check the OBJ file " + found_text(utf8_text(relative)));
        triangles_ += m.triangles.size();
        m.source = utf8_text(relative);
        for (vec3& p : m.positions) {
            p = p * scale + translate;
            // the OBJ reader's limit holds after scale and translate too: beyond it
            // the triangle tests' products overflow and the mesh would vanish
            const real largest = std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
            if (!(double(largest) <= options_.obj.max_coordinate))
                throw parse_error(where, "a mesh within +-" + detail::short_number(options_.obj.max_coordinate) +
                                             " after its scale and translate",
                                  "a vertex at " + detail::short_number(double(largest)),
                                  "float arithmetic cannot trace coordinates that large; use a smaller scale");
        }
        if (material_index != -2) {
            m.material = material_index;
            m.face_materials.clear();
        } else {
            const int offset = int(result_.materials.size());
            for (int& id : m.face_materials)
                id = id < 0 ? -1 : id + offset;
            result_.materials.insert(result_.materials.end(), loaded.materials.begin(), loaded.materials.end());
        }
        result_.shapes.emplace_back(std::move(m));
    }

    void read_light(statement& line)
    {
        const std::string kind = line.word("a light type (point, directional, rect or sphere)");
        light l;
        if (kind == "point") {
            l.kind = light_kind::point;
            line.options({"position", "intensity"}, [&](const std::string& option) {
                if (option == "position")
                    l.position = line.vector("position");
                else
                    l.intensity = line.rgb("intensity");
            });
        } else if (kind == "directional") {
            l.kind = light_kind::directional;
            line.options({"direction", "intensity"}, [&](const std::string& option) {
                if (option == "direction")
                    l.direction = line.direction("direction");
                else
                    l.intensity = line.rgb("intensity");
            });
        } else if (kind == "rect") {
            l.kind = light_kind::rect;
            line.options({"corner", "edge1", "edge2", "intensity"}, [&](const std::string& option) {
                if (option == "corner")
                    l.position = line.vector("corner");
                else if (option == "edge1")
                    l.edge1 = line.vector("edge1");
                else if (option == "edge2")
                    l.edge2 = line.vector("edge2");
                else
                    l.intensity = line.rgb("intensity");
            });
            const real area = glm::length(glm::cross(l.edge1, l.edge2));
            if (!(area > 0))
                throw parse_error(line.line_start(), "a rect light with an area", "edges that are parallel or zero",
                                  "edge1 and edge2 are two sides from the corner, e.g. edge1 1 0 0 edge2 0 0 1");
        } else if (kind == "sphere") {
            l.kind = light_kind::sphere;
            line.options({"center", "radius", "intensity"}, [&](const std::string& option) {
                if (option == "center")
                    l.position = line.vector("center");
                else if (option == "radius") {
                    const source_location where = line.here();
                    l.radius = line.number("radius");
                    if (!(l.radius > 0))
                        throw parse_error(where, "a positive radius", detail::short_number(double(l.radius)),
                                          "a light of radius 0 is a point light: use light point");
                } else
                    l.intensity = line.rgb("intensity");
            });
        } else {
            throw parse_error(line.last(), "a light type (point, directional, rect or sphere)", found_text(kind),
                              nearest_hint(kind, {"point", "directional", "rect", "sphere"}));
        }
        result_.lights.push_back(l);
    }

    void read_lens(statement& line)
    {
        if (lens_at_)
            throw parse_error(line.line_start(), "one lens", "a second lens statement",
                              "a camera has one lens; delete one");
        lens_at_ = line.line_start();
        line.options({"aperture", "focus"}, [&](const std::string& option) {
            const source_location where = line.here();
            if (option == "aperture") {
                const real aperture = line.number("the lens radius (aperture)");
                if (!(aperture >= 0))
                    throw parse_error(where, "an aperture of 0 or more", detail::short_number(double(aperture)),
                                      "it is the lens radius; 0 is a pinhole");
                result_.lens.aperture = aperture;
            } else {
                const real focus = line.number("the focus distance");
                if (!(focus > 0))
                    throw parse_error(where, "a positive focus distance", detail::short_number(double(focus)),
                                      "it is the distance from the eye to the plane in focus");
                result_.lens.focus = focus;
                focus_given_ = true;
            }
        });
    }

    std::string file_;
    std::filesystem::path folder_;
    load_options options_;
    scene result_;
    std::optional<source_location> lens_at_;
    bool focus_given_ = false;
    bool seen_camera_ = false;
    bool seen_image_ = false;
    int statements_ = 0;
    std::size_t triangles_ = 0; ///< triangles of the meshes read so far
};

inline scene load_scene_stream(std::istream& in, const std::string& name, const std::filesystem::path& folder,
                               const load_options& options)
{
    scene_reader reader(name, folder, options);
    std::string text;
    int number = 0;
    while (read_bounded_line(in, text, options.max_line_length)) {
        if (number == std::numeric_limits<int>::max())
            throw error(source_location{name, number}, "expected at most " + std::to_string(number) +
                                                           " lines, found more; split the scene");
        if (number == 0 && text.compare(0, 3, "\xEF\xBB\xBF") == 0)
            text.erase(0, 3); // a UTF-8 byte order mark, skipped as in OBJ and MTL files (obj_loader.hpp)
        reader.read_line(text, ++number);
    }
    if (in.bad())
        throw error(source_location{name, number}, "reading failed; is the file complete?");
    return reader.finish(number);
}

} // namespace detail

/// Parses scene text; `name` is used in messages, and mesh paths are relative to `folder`.
inline scene load_scene_from_string(const std::string& text, const std::string& name = "<string>",
                                    const std::filesystem::path& folder = ".", const load_options& options = {})
{
    std::istringstream in(text);
    return detail::load_scene_stream(in, name, folder, options);
}

/// Loads a scene file. Throws rt::error with file:line:col on any problem.
inline scene load_scene(const std::filesystem::path& path, const load_options& options = {})
{
    const std::string name = detail::utf8_text(path);
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw error(source_location{name}, "expected a scene file, found a folder; name the .scene file itself");
    if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
        throw error(source_location{name}, "expected a scene file, found a device, pipe or socket; "
                                           "name a .scene file (a special file could block or never end)");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw error(source_location{name}, std::filesystem::exists(path, ec)
                                               ? "expected a readable scene file, found one that cannot be opened; check its permissions"
                                               : "expected a scene file, found no such file; check the path");
    return detail::load_scene_stream(in, name, detail::scene_folder(path), options);
}

} // namespace rt
