// scene_loader.hpp - read a scene file (stage 01).
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
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

#include "camera_model.hpp"
#include "error.hpp"
#include "obj_loader.hpp"
#include "scene.hpp"

namespace rt {

/// Limits the loader checks before allocating anything, and how to raise them.
struct load_options {
    std::int64_t max_pixels = std::int64_t(1) << 26;  ///< 67 million pixels (8192 x 8192)
    int max_depth = 64;                               ///< the largest max_depth a file may ask for
    int max_samples = 1 << 16;                        ///< the largest samples per pixel
    std::size_t max_line_length = 4096;               ///< characters in one line
    obj_limits obj;                                   ///< limits for the OBJ files a scene names
};

/// One word of a line and the column (from 1) where it starts.
struct token {
    std::string text;
    int column = 0;
};

/// The length of the shortest edit from a to b (Levenshtein), for "did you mean".
inline std::size_t edit_distance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

/// Shortens what a file contained for an error message, so a message never
/// dumps file contents: at most 24 printable characters, quoted.
inline std::string found_text(const std::string& text)
{
    std::string shown;
    for (char c : text.substr(0, 24))
        shown += (c >= 32 && c < 127) ? c : '?';
    return "'" + shown + (text.size() > 24 ? "...'" : "'");
}

/// "did you mean 'x'?" for the known word closest to `word`, or a short list of
/// them. The work and the message are bounded whatever the file declares: the
/// distance compares the first 64 characters of each word (a typo is found
/// there), and the list shows at most 8 names, each shortened by found_text.
inline std::string nearest_hint(const std::string& word, const std::vector<std::string>& known)
{
    if (known.empty())
        return "none is declared yet";
    const std::size_t compared = 64;
    const std::string prefix = word.substr(0, compared);
    std::size_t best = 0, best_distance = std::numeric_limits<std::size_t>::max();
    for (std::size_t i = 0; i < known.size(); ++i) {
        const std::size_t distance = edit_distance(prefix, known[i].substr(0, compared));
        if (distance < best_distance) {
            best = i;
            best_distance = distance;
        }
    }
    if (best_distance <= std::max<std::size_t>(2, prefix.size() / 3))
        return "did you mean " + found_text(known[best]) + "?";
    const std::size_t listed = 8;
    std::string list;
    for (std::size_t i = 0; i < known.size() && i < listed; ++i)
        list += (list.empty() ? "" : ", ") + found_text(known[i]);
    if (known.size() > listed)
        list += " and " + std::to_string(known.size() - listed) + " more";
    return "known: " + list;
}

/// One statement of a scene file, read left to right. Each reader names what it
/// expects, so its error message can say it.
class statement {
public:
    statement(std::string file, int line, std::vector<token> tokens, int end_column)
        : file_(std::move(file)), line_(line), tokens_(std::move(tokens)), end_column_(end_column) {}

    const std::string& keyword() const { return tokens_.front().text; }
    /// Where the next unread token starts (or the end of the line).
    source_location here() const { return {file_, line_, next_ < tokens_.size() ? tokens_[next_].column : end_column_}; }
    source_location line_start() const { return {file_, line_, tokens_.front().column}; }
    /// Where the token just read starts.
    source_location last() const { return {file_, line_, tokens_[next_ - 1].column}; }
    bool done() const { return next_ >= tokens_.size(); }
    const std::string& peek() const { return tokens_[next_].text; }

    /// An error at the next unread token: "expected <expected>, found <that token>".
    error unexpected(const std::string& expected, const std::string& hint = {}) const
    {
        return parse_error(here(), expected, done() ? "the end of the line" : found_text(peek()), hint);
    }

    std::string word(const std::string& what)
    {
        if (done())
            throw unexpected(what);
        return tokens_[next_++].text;
    }

    /// A finite number (NaN, inf and numbers beyond rt::real's range are errors).
    real number(const std::string& what)
    {
        if (done())
            throw unexpected("a number for " + what);
        const std::string& text = peek();
        double value = 0;
        const char* first = text.data();
        const char* last = first + text.size();
        if (!text.empty() && *first == '+')
            ++first;
        const auto [end, status] = std::from_chars(first, last, value);
        if (status == std::errc() && end == last && !std::isfinite(value))
            throw unexpected("a finite number for " + what, "NaN and inf are not allowed");
        if (status == std::errc::result_out_of_range ||
            (status == std::errc() && end == last && std::fabs(value) > double(std::numeric_limits<real>::max()))) {
            std::ostringstream limit;
            limit << std::numeric_limits<real>::max();
            throw unexpected("a number for " + what + " within +-" + limit.str(), "use smaller units");
        }
        if (status != std::errc() || end != last)
            throw unexpected("a number for " + what);
        ++next_;
        return real(value);
    }

    /// A whole number in [low, high]; `limit_hint` says how to raise `high`.
    int integer(const std::string& what, int low, int high, const std::string& limit_hint = {})
    {
        if (done())
            throw unexpected("a whole number for " + what);
        const std::string& text = peek();
        long long value = 0;
        const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (status != std::errc() || end != text.data() + text.size())
            throw unexpected("a whole number for " + what);
        if (value < low || value > high)
            throw unexpected(what + " between " + std::to_string(low) + " and " + std::to_string(high),
                             value > high ? limit_hint : std::string());
        ++next_;
        return int(value);
    }

    vec3 vector(const std::string& what)
    {
        vec3 v;
        v.x = number(what + " x");
        v.y = number(what + " y");
        v.z = number(what + " z");
        return v;
    }

    /// A vector that must not be zero (a direction).
    vec3 direction(const std::string& what)
    {
        const source_location where = here();
        const vec3 v = vector(what);
        if (glm::dot(v, v) == real(0))
            throw parse_error(where, "a non-zero " + what, "0 0 0", "a direction needs a length");
        return v;
    }

    /// An RGB colour with non-negative components.
    color rgb(const std::string& what)
    {
        color c;
        for (int channel = 0; channel < 3; ++channel) {
            const source_location where = here();
            const real value = number(what + " " + "rgb"[channel]);
            if (value < 0)
                throw parse_error(where, "a non-negative " + what, std::to_string(value), "colours cannot be negative");
            c[channel] = float(value);
        }
        return c;
    }

    /// Reads "option value..." pairs until the end of the line; `read(option)`
    /// consumes the value of a known option and returns false for an unknown one.
    template <class Reader>
    void options(const std::vector<std::string>& known, Reader&& read)
    {
        while (!done()) {
            const std::string option = peek();
            if (std::find(known.begin(), known.end(), option) == known.end())
                throw unexpected("an option of '" + keyword() + "'", nearest_hint(option, known));
            ++next_;
            read(option);
        }
    }

    /// Requires that nothing is left on the line.
    void end() const
    {
        if (!done())
            throw unexpected("the end of the line", "'" + keyword() + "' takes fewer arguments");
    }

private:
    std::string file_;
    int line_;
    std::vector<token> tokens_;
    int end_column_;
    std::size_t next_ = 1; // tokens_[0] is the keyword
};

/// Reads a camera statement into `cam`:
///     camera perspective|orthographic [eye x y z] [look_at x y z] [up x y z]
///                                     [fov degrees] [window l r b t] [focal d]
/// and checks that it describes a camera: e differs from look_at, up is not
/// parallel to the view direction, fov in (0, 180), l < r, b < t, d > 0.
inline void parse_camera(statement& line, camera& cam)
{
    // RT_EXERCISE_BEGIN(stage01: load the camera)
    const std::string kind = line.word("a camera type (perspective or orthographic)");
    if (kind == "perspective")
        cam.kind = projection::perspective;
    else if (kind == "orthographic")
        cam.kind = projection::orthographic;
    else
        throw parse_error(line.last(), "a camera type (perspective or orthographic)", found_text(kind),
                          nearest_hint(kind, {"perspective", "orthographic"}));

    source_location view_at = line.line_start(), up_at = line.line_start();
    line.options({"eye", "look_at", "up", "fov", "window", "focal"}, [&](const std::string& option) {
        const source_location where = line.here();
        if (option == "eye") {
            cam.eye = line.vector("eye");
            view_at = where;
        } else if (option == "look_at") {
            cam.look_at = line.vector("look_at");
            view_at = where;
        } else if (option == "up") {
            cam.up = line.direction("up");
            up_at = where;
        } else if (option == "fov") {
            const real fov = line.number("fov");
            if (!(fov > 0 && fov < 180))
                throw parse_error(where, "a field of view between 0 and 180 degrees", std::to_string(fov));
            if (cam.kind == projection::orthographic)
                throw parse_error(where, "a window for an orthographic camera", "fov",
                                  "fov applies to perspective cameras only; use window l r b t");
            cam.fov_degrees = fov;
        } else if (option == "window") {
            window win;
            win.l = line.number("window l");
            win.r = line.number("window r");
            win.b = line.number("window b");
            win.t = line.number("window t");
            if (!(win.l < win.r) || !(win.b < win.t))
                throw parse_error(where, "a window with l < r and b < t", "an empty window");
            cam.plane = win;
        } else { // focal
            cam.focal_distance = line.number("focal distance");
            if (!(cam.focal_distance > 0))
                throw parse_error(where, "a positive focal distance", std::to_string(cam.focal_distance));
        }
    });
    if (cam.fov_degrees && cam.plane)
        throw parse_error(line.line_start(), "either fov or window", "both", "give one of them");
    const vec3 view = cam.look_at - cam.eye;
    if (glm::dot(view, view) == real(0))
        throw parse_error(view_at, "a look_at point different from the eye", "the same point",
                          "the camera needs a direction to look in");
    // The frame normalises look_at - eye, which squares its length: past about
    // 1e19 in float that square overflows and every ray would be NaN.
    if (!std::isfinite(glm::dot(view, view)))
        throw parse_error(view_at, "an eye within about 1e19 of look_at (the square of the distance must fit rt::real)",
                          "a distance whose square overflows",
                          "move the scene nearer the origin, or build with -DRT_USE_DOUBLE=ON");
    // the frame normalises up x w too: |up|^2 must be a normal, finite number
    const real up_squared = glm::dot(cam.up, cam.up);
    if (!(up_squared >= std::numeric_limits<real>::min() && std::isfinite(up_squared)))
        throw parse_error(up_at, "an up vector whose squared length fits rt::real (a length from about 1e-19 to 1e19)",
                          "one of length " + detail::short_number(double(glm::length(glm::dvec3(cam.up)))),
                          "the length of up does not matter: use 0 1 0 or 0 0 1");
    // up and the view direction scaled to a largest coordinate of 1 first, so
    // that neither a huge nor a tiny vector overflows the test (the test is
    // sin^2 of their angle > 1e-12)
    auto scaled = [](const vec3& a) {
        return a / std::max(std::fabs(a.x), std::max(std::fabs(a.y), std::fabs(a.z)));
    };
    const vec3 up = scaled(cam.up), ahead = scaled(view);
    const vec3 side = glm::cross(up, ahead);
    if (!(glm::dot(side, side) > real(1e-12) * glm::dot(ahead, ahead) * glm::dot(up, up)))
        throw parse_error(up_at, "an up vector not parallel to the view direction", "a parallel one",
                          "choose an up vector that differs from look_at - eye, such as 0 1 0 or 0 0 1");
    // RT_EXERCISE_END
}

namespace detail {

/// The length of the well-formed UTF-8 sequence that starts at text[i], or 0
/// when the bytes there are not one. The Unicode Standard, Version 15.0,
/// sec. 3.9, Table 3-7 "Well-Formed UTF-8 Byte Sequences" (also RFC 3629, sec. 4).
inline std::size_t utf8_length(const std::string& text, std::size_t i)
{
    const auto byte = [&](std::size_t k) {
        return k < text.size() ? unsigned(static_cast<unsigned char>(text[k])) : 0u;
    };
    const auto in = [](unsigned b, unsigned low, unsigned high) { return b >= low && b <= high; };
    const unsigned b0 = byte(i), b1 = byte(i + 1), b2 = byte(i + 2), b3 = byte(i + 3);
    if (b0 < 0x80)
        return 1;
    if (in(b0, 0xC2, 0xDF))
        return in(b1, 0x80, 0xBF) ? 2 : 0;
    if (b0 == 0xE0)
        return in(b1, 0xA0, 0xBF) && in(b2, 0x80, 0xBF) ? 3 : 0;
    if (in(b0, 0xE1, 0xEC) || in(b0, 0xEE, 0xEF))
        return in(b1, 0x80, 0xBF) && in(b2, 0x80, 0xBF) ? 3 : 0;
    if (b0 == 0xED)
        return in(b1, 0x80, 0x9F) && in(b2, 0x80, 0xBF) ? 3 : 0;
    if (b0 == 0xF0)
        return in(b1, 0x90, 0xBF) && in(b2, 0x80, 0xBF) && in(b3, 0x80, 0xBF) ? 4 : 0;
    if (in(b0, 0xF1, 0xF3))
        return in(b1, 0x80, 0xBF) && in(b2, 0x80, 0xBF) && in(b3, 0x80, 0xBF) ? 4 : 0;
    if (b0 == 0xF4)
        return in(b1, 0x80, 0x8F) && in(b2, 0x80, 0xBF) && in(b3, 0x80, 0xBF) ? 4 : 0;
    return 0;
}

/// Requires that text[from, to) is text: printable ASCII, tabs, or well-formed
/// UTF-8 (for names and paths in other languages); control bytes and other
/// bytes mean the file is not a scene file.
inline void check_text(const std::string& text, std::size_t from, std::size_t to, const source_location& where)
{
    for (std::size_t i = from; i < to;) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        const std::size_t length = (c < 32 && c != '\t' && c != '\r') || c == 127 ? 0 : utf8_length(text, i);
        if (length == 0 || i + length > to)
            throw parse_error({where.file, where.line, int(i) + 1}, "plain text (ASCII or UTF-8)",
                              "a byte of value " + std::to_string(int(c)), "is this a scene file?");
        i += length;
    }
}

/// Splits one line into tokens: words separated by blanks, "quoted strings"
/// (for paths with spaces), and a '#' that starts a comment (which may hold
/// anything but is not read).
inline std::vector<token> tokenize(const std::string& text, const source_location& where)
{
    std::vector<token> tokens;
    std::size_t i = 0;
    while (i < text.size()) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c == ' ' || c == '\t' || c == '\r') {
            ++i;
        } else if (c == '#') {
            break;
        } else if (c == '"') {
            const std::size_t close = text.find('"', i + 1);
            if (close == std::string::npos)
                throw parse_error({where.file, where.line, int(i) + 1}, "a closing '\"'", "the end of the line");
            check_text(text, i + 1, close, where);
            tokens.push_back({text.substr(i + 1, close - i - 1), int(i) + 1});
            i = close + 1;
        } else {
            const std::size_t start = i;
            while (i < text.size() && text[i] != ' ' && text[i] != '\t' && text[i] != '\r' && text[i] != '#')
                ++i;
            check_text(text, start, i, where);
            tokens.push_back({text.substr(start, i - start), int(start) + 1});
        }
    }
    return tokens;
}

/// Reads the next line of `in` into `text`, without its line break, but never
/// more than `limit` + 1 characters, so that a file without line breaks cannot
/// exhaust memory (the caller rejects a line longer than `limit`). A line ends
/// at LF, CR LF or a lone CR (classic Mac OS files), so line numbers are right
/// whichever a file uses. Returns false at the end of the input, as
/// std::getline does.
inline bool read_bounded_line(std::istream& in, std::string& text, std::size_t limit)
{
    text.clear();
    char c = 0;
    while (in.get(c)) {
        if (c == '\n')
            return true;
        if (c == '\r') {
            if (in.peek() == '\n')
                in.get(c);
            return true;
        }
        text += c;
        if (text.size() > limit)
            return true;
    }
    return !text.empty();
}

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
    static const std::vector<std::string> words = {"image",  "camera",  "material",   "sphere",  "triangle", "mesh",
                                                   "light",  "ambient", "background", "samples", "max_depth"};
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
        bool ambient_given = false;
        line.options({"ka", "kd", "ks", "p", "km"}, [&](const std::string& option) {
            if (option == "ka") {
                m.ka = line.rgb("ka");
                ambient_given = true;
            } else if (option == "kd")
                m.kd = line.rgb("kd");
            else if (option == "ks")
                m.ks = line.rgb("ks");
            else if (option == "km")
                m.km = line.rgb("km");
            else {
                const source_location where = line.here();
                m.p = line.number("Phong exponent p");
                if (m.p < 0)
                    throw parse_error(where, "a non-negative Phong exponent", std::to_string(m.p));
            }
        });
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
        tri.a = line.vector("corner a");
        tri.b = line.vector("corner b");
        tri.c = line.vector("corner c");
        if (triangle_normal(tri.a, tri.b, tri.c) == vec3(0)) // the library's normal (triangle_shape.hpp)
            throw parse_error(where, "a triangle with non-zero area", "three corners on one line",
                              "check the corners");
        line.options({"material"}, [&](const std::string&) { tri.material = find_material(result_, line); });
        result_.shapes.emplace_back(tri);
    }

    void read_mesh(statement& line)
    {
        const source_location where = line.here();
        const std::filesystem::path relative = line.word("an OBJ file path");
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
                              "check the OBJ file " + found_text(relative.string()));
        triangles_ += m.triangles.size();
        m.source = relative.string();
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
        const std::string kind = line.word("a light type (point or directional)");
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
        } else {
            throw parse_error(line.last(), "a light type (point or directional)", found_text(kind),
                              nearest_hint(kind, {"point", "directional"}));
        }
        result_.lights.push_back(l);
    }

    std::string file_;
    std::filesystem::path folder_;
    load_options options_;
    scene result_;
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
    const std::string name = path.string();
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

/// The files load_scene(path) read to make `s`: the scene file and the OBJ file
/// of each mesh. A program that writes an output checks it against them first
/// (rt::check_not_input), so a mistyped command line cannot overwrite an input.
inline std::vector<std::filesystem::path> input_files(const std::filesystem::path& path, const scene& s)
{
    std::vector<std::filesystem::path> files{path};
    for (const shape& item : s.shapes)
        if (const mesh* m = std::get_if<mesh>(&item))
            files.push_back(detail::mesh_path(detail::scene_folder(path), m->source));
    return files;
}

} // namespace rt
