// scene_loader.hpp - read a scene file (stage 01).
//
// The entry point: load_scene, load_scene_from_string and load_options, and the
// reader that sends each line to its statement. The words of a line:
// scene_statement.hpp. The statements: camera_statement.hpp (the stage-01
// exercise), material_statement.hpp, shape_statements.hpp (sphere, triangle,
// mesh) and light_statement.hpp; image, lens and the one-value statements here.
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

#include "../scene/camera_model.hpp"
#include "camera_statement.hpp"
#include "../core/error.hpp"
#include "light_statement.hpp"
#include "material_statement.hpp"
#include "obj_check.hpp"
#include "../system/path_text.hpp"
#include "../scene/scene.hpp"
#include "scene_statement.hpp"
#include "shape_statements.hpp"
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

/// The folder a scene file's relative paths start from: its parent, or the
/// empty path (the working directory, which messages then leave out) for a
/// scene file named without a folder.
inline std::filesystem::path scene_folder(const std::filesystem::path& scene_file)
{
    return scene_file.parent_path();
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
            throw make_error(where, "a line of at most " + std::to_string(options_.max_line_length) + " characters",
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
            throw make_error({file_, std::max(lines, 1), 1}, "at least one statement", "an empty file",
                             "see docs/scene-format.md for an example scene");
        if (lens_at_) {
            if (result_.cam.kind != projection::perspective && result_.lens.aperture > 0)
                throw make_error(*lens_at_, "a lens in front of a perspective camera", "an orthographic camera",
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
                throw make_error(line.line_start(), "one camera", "a second camera statement",
                                 "a scene has exactly one camera; delete one");
            seen_camera_ = true;
            parse_camera(line, result_.cam);
        } else if (keyword == "material")
            result_.materials.push_back(read_material(line, result_.materials));
        else if (keyword == "sphere")
            result_.shapes.emplace_back(read_sphere(line, result_));
        else if (keyword == "triangle")
            result_.shapes.emplace_back(read_triangle(line, result_, options_.obj.max_coordinate));
        else if (keyword == "mesh")
            read_mesh(line, result_, folder_, options_.obj, triangles_);
        else if (keyword == "light")
            result_.lights.push_back(read_light(line));
        else if (keyword == "ambient")
            result_.ambient = line.rgb("ambient intensity");
        else if (keyword == "background")
            result_.background = line.rgb("background color");
        else if (keyword == "samples")
            result_.samples = line.integer("samples per pixel", 1, options_.max_samples,
                                           "the limit is load_options::max_samples; raise it if you mean it");
        else if (keyword == "lens")
            read_lens(line);
        else if (keyword == "max_depth")
            result_.max_depth = line.integer("max_depth", 0, options_.max_depth,
                                             "the limit is load_options::max_depth; raise it if you mean it");
        else
            throw make_error(line.line_start(), "a keyword", found_text(keyword), nearest_hint(keyword, keywords()));
    }

    void read_image(statement& line)
    {
        if (seen_image_)
            throw make_error(line.line_start(), "one image statement", "a second one", "delete one of them");
        seen_image_ = true;
        const source_location where = line.here();
        const int width = line.integer("image width", 1, 1 << 20);
        const int height = line.integer("image height", 1, 1 << 20);
        if (std::int64_t(width) * height > options_.max_pixels)
            throw make_error(where, "at most " + std::to_string(options_.max_pixels) + " pixels",
                             std::to_string(width) + "x" + std::to_string(height),
                             "raise load_options::max_pixels if you mean it");
        result_.width = width;
        result_.height = height;
    }

    void read_lens(statement& line)
    {
        if (lens_at_)
            throw make_error(line.line_start(), "one lens", "a second lens statement",
                             "a camera has one lens; delete one");
        lens_at_ = line.line_start();
        line.options({"aperture", "focus"}, [&](const std::string& option) {
            const source_location where = line.here();
            if (option == "aperture") {
                const real aperture = line.number("the lens radius (aperture)");
                if (!(aperture >= 0))
                    throw make_error(where, "an aperture of 0 or more", detail::short_number(double(aperture)),
                                     "it is the lens radius; 0 is a pinhole");
                result_.lens.aperture = aperture;
            } else {
                const real focus = line.number("the focus distance");
                if (!(focus > 0))
                    throw make_error(where, "a positive focus distance", detail::short_number(double(focus)),
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
