// obj_loader.hpp - Wavefront OBJ meshes through tinyobjloader (stage 04).
//
// tinyobjloader (Debian's libtinyobjloader, linked through rt::rt) parses the
// file; this header turns its output into an rt::mesh that stores only what the
// file provides, triangulates polygons (fans), drops zero-area triangles with a
// count, maps MTL colours to rt materials, and reports every problem as one
// line "file:line: expected ..., found ...; hint". Before tinyobjloader reads a
// file, detail::check_obj_text reads it once to reject, with the line, what
// tinyobjloader would drop silently or cannot read safely (issue 8).
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <tiny_obj_loader.h>

#include "error.hpp"
#include "material.hpp"
#include "mesh.hpp"

namespace rt {

/// What loading an OBJ file gives: the mesh and the materials of its MTL files
/// (mesh::face_materials index into `materials`).
struct obj_result {
    mesh geometry;
    std::vector<material> materials;
};

/// Limits checked before allocating, so a hostile file cannot exhaust memory.
struct obj_limits {
    std::size_t max_triangles = std::size_t(1) << 26;  ///< 67 million
    std::size_t max_line_length = std::size_t(1) << 20; ///< characters in one line
};

namespace detail {

/// The 1-based line of the `face_number`-th face statement ("f ...") of an OBJ
/// file, or 0 when it cannot be found; used only to point an error message at
/// the right line (tinyobjloader does not report face lines).
inline int obj_face_line(const std::filesystem::path& path, std::size_t face_number)
{
    std::ifstream in(path);
    std::string text;
    std::size_t faces = 0;
    for (int line = 1; std::getline(in, text); ++line) {
        std::size_t first = text.find_first_not_of(" \t");
        if (first != std::string::npos && text[first] == 'f' && first + 1 < text.size() &&
            (text[first + 1] == ' ' || text[first + 1] == '\t')) {
            if (faces == face_number)
                return line;
            ++faces;
        }
    }
    return 0;
}

/// A tinyobjloader message (possibly several lines) as one short line: line
/// breaks become blanks, other bytes that are not printable ASCII become '?'
/// (its messages quote names from the file), and it keeps its first 200
/// characters, so a message never dumps file contents.
inline std::string one_line(std::string text)
{
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r'))
        text.pop_back();
    const std::size_t keep = 200;
    if (text.size() > keep)
        text = text.substr(0, keep) + "...";
    for (char& c : text)
        if (c == '\n' || c == '\r')
            c = ' ';
        else if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) >= 127)
            c = '?';
    return text;
}

/// Calls `read(text, line)` for each line of an OBJ or MTL file, split as
/// tinyobjloader splits them (LF, CR LF or a lone CR), after checking that the
/// line is text and at most limits.max_line_length characters long. It keeps
/// one line at a time, so its memory does not grow with the file.
template <class Reader>
void for_each_obj_line(const std::filesystem::path& path, const obj_limits& limits, Reader&& read)
{
    const std::string name = path.string();
    std::ifstream in(path, std::ios::binary);
    std::vector<char> chunk(std::size_t(1) << 16);
    std::string text;
    int line = 1;
    bool after_cr = false; // a '\n' right after a '\r' ends no second line
    while (in.read(chunk.data(), std::streamsize(chunk.size())) || in.gcount() > 0) {
        const std::size_t size = std::size_t(in.gcount());
        for (std::size_t i = 0; i < size;) {
            // A run of ordinary characters is appended at once.
            std::size_t end = i;
            while (end < size && (static_cast<unsigned char>(chunk[end]) >= 32 || chunk[end] == '\t') &&
                   chunk[end] != 127)
                ++end;
            text.append(chunk.data() + i, end - i);
            if (end > i)
                after_cr = false;
            if (text.size() > limits.max_line_length)
                throw parse_error({name, line},
                                  "a line of at most " + std::to_string(limits.max_line_length) + " characters",
                                  "a longer one", "the limit is obj_limits::max_line_length; raise it if you mean it");
            if (end == size)
                break;
            const char c = chunk[end];
            i = end + 1;
            const bool skip = after_cr && c == '\n';
            after_cr = c == '\r';
            if (skip)
                continue;
            if (c == '\n' || c == '\r') {
                read(std::as_const(text), line);
                text.clear();
                ++line;
                continue;
            }
            if (c != '\v' && c != '\f')
                throw parse_error({name, line, int(text.size()) + 1}, "text",
                                  "a byte of value " + std::to_string(int(static_cast<unsigned char>(c))),
                                  "is this an OBJ or MTL file?");
            text += c;
        }
    }
    if (!text.empty())
        read(std::as_const(text), line);
}

/// One blank-separated word of a line and its column (from 0).
struct obj_word {
    std::string_view text;
    std::size_t column = 0;
};

/// Fills `words` with the words of a line; none for a comment line.
/// (tinyobjloader skips a line that starts with '#', but reads on past a '#'
/// later in a line.)
inline void obj_words(std::string_view text, std::vector<obj_word>& words)
{
    words.clear();
    const auto blank = [](char c) { return c == ' ' || c == '\t'; };
    for (std::size_t at = 0; at < text.size();) {
        if (blank(text[at])) {
            ++at;
            continue;
        }
        if (words.empty() && text[at] == '#')
            return;
        std::size_t end = at;
        while (end < text.size() && !blank(text[end]))
            ++end;
        words.push_back({text.substr(at, end - at), at});
        at = end;
    }
}

/// Up to 24 characters of a word for a message.
inline std::string shown_word(std::string_view word)
{
    return "'" + one_line(std::string(word.substr(0, 24))) + "'";
}

/// Checks the number a word starts with, if it starts like one for
/// tinyobjloader's tryParseDouble ([+-] then a digit or '.'): its value must
/// fit tinyobjloader's float (real_t), and the exponent it spells must be at
/// most 400. tinyobjloader converts a double beyond float's range to float and
/// adds up the exponent's digits in an int; both are undefined behaviour
/// (C++17 [conv.double]/1, [expr]/4), so such numbers never reach it.
/// `whole`: the word must be one finite number and nothing else.
inline void check_obj_number(std::string_view word, const std::string& file, int line, int column, bool whole)
{
    const char* first = word.data();
    const char* last = first + word.size();
    if (first != last && (*first == '+' || *first == '-'))
        ++first;
    const auto digit = [&](const char* at) { return at != last && *at >= '0' && *at <= '9'; };
    const bool numeric = digit(first) || (first != last && *first == '.');
    if (!numeric && !whole)
        return;
    // The exponent as tryParseDouble reads it: digits [. digits] e|E [+-] digits.
    const char* at = first;
    while (digit(at))
        ++at;
    if (at != last && *at == '.')
        for (++at; digit(at); ++at) {
        }
    long long exponent = 0;
    if (at != last && (*at == 'e' || *at == 'E')) {
        if (++at != last && (*at == '+' || *at == '-'))
            ++at;
        for (; digit(at); ++at)
            exponent = std::min<long long>(exponent * 10 + (*at - '0'), 100000);
    }
    double value = 0;
    const auto [end, status] = std::from_chars(first, last, value);
    if (numeric && (status == std::errc::result_out_of_range || exponent > 400 ||
                    std::fabs(value) > double(std::numeric_limits<tinyobj::real_t>::max())))
        throw parse_error({file, line, column}, "a number that fits a float", shown_word(word), "use smaller units");
    if (!numeric || (whole && (status != std::errc() || end != last || !std::isfinite(value))))
        throw parse_error({file, line, column}, "a finite number", shown_word(word),
                          "NaN, inf and other words are not coordinates");
}

/// One index of a face corner "v", "v/vt", "v//vn" or "v/vt/vn" from text[at]
/// on (a sign is allowed, 0 is not): true and the value, or false.
inline bool obj_index(std::string_view text, std::size_t& at, long long& value)
{
    const char* first = text.data() + at;
    const char* last = text.data() + text.size();
    if (first != last && *first == '+')
        ++first;
    const auto [end, status] = std::from_chars(first, last, value);
    if (status != std::errc() || value == 0 || value < std::numeric_limits<int>::min() ||
        value > std::numeric_limits<int>::max())
        return false;
    at = std::size_t(end - text.data());
    return true;
}

/// Reads an OBJ file (and the MTL files it names) once, before tinyobjloader
/// does, and rejects with "file:line: ..." what tinyobjloader would skip
/// silently, misreport, allocate for or misbehave on: a byte that is not text,
/// a line longer than limits.max_line_length, a vertex coordinate that is not
/// a finite float, a face of fewer than 3 corners, an index that is 0, not a
/// number or outside the vertices (texture coordinates, normals) of the file,
/// more than limits.max_triangles triangles (a face of n corners makes n - 2),
/// a material library that is missing or not a regular file, and numbers that
/// tinyobjloader cannot convert safely (check_obj_number). Statements are
/// recognised as tinyobjloader's LoadObj does: leading blanks skipped, then a
/// keyword followed by a blank.
inline void check_obj_text(const std::filesystem::path& path, const obj_limits& limits)
{
    const std::string name = path.string();
    // Indices count from 1 in file order; a negative one counts back from the
    // last element read so far (Wavefront OBJ specification, "Referencing groups of vertices").
    const char* const kinds[3] = {"vertex", "texture coordinate", "normal"};
    std::size_t counts[3] = {0, 0, 0};
    long long largest[3] = {0, 0, 0};
    int largest_line[3] = {0, 0, 0};
    std::size_t triangles = 0;
    std::vector<obj_word> words;
    for_each_obj_line(path, limits, [&](const std::string& text, int line) {
        obj_words(text, words);
        if (words.empty())
            return;
        // tinyobjloader's keywords are followed by a blank, never by the end of the line.
        const bool blank_after = words.front().column + words.front().text.size() < text.size();
        const std::string_view keyword = blank_after ? words.front().text : std::string_view();
        const bool coordinates = keyword == "v" || keyword == "vt" || keyword == "vn";
        // x y z of "v" and "vn" (u [v [w]] of "vt") are finite numbers, up to a trailing comment.
        const std::size_t required = keyword == "vt" ? 1 : 3;
        std::size_t numbers = 0;
        for (std::size_t i = 1; i < words.size(); ++i) {
            const bool strict = coordinates && i <= 3 && numbers + 1 == i && words[i].text[0] != '#';
            check_obj_number(words[i].text, name, line, int(words[i].column) + 1, strict);
            numbers += strict ? 1 : 0;
        }
        if (coordinates && numbers < required)
            throw parse_error({name, line, int(text.size()) + 1},
                              std::to_string(required) + " coordinate(s) after '" + std::string(keyword) + "'",
                              std::to_string(numbers), "is the line cut short?");
        if (coordinates) {
            ++counts[keyword == "v" ? 0 : keyword == "vt" ? 1 : 2];
        } else if (keyword == "f") {
            for (std::size_t i = 1; i < words.size(); ++i) {
                const std::string_view corner = words[i].text;
                const int column = int(words[i].column) + 1;
                std::size_t at = 0;
                for (int kind = 0; kind < 3; ++kind) {
                    if (kind > 0) { // "/vt" and "/vn"; "//vn" has no texture coordinate
                        if (at >= corner.size() || corner[at] != '/')
                            break;
                        ++at;
                        if (kind == 1 && at < corner.size() && corner[at] == '/')
                            continue;
                    }
                    long long value = 0;
                    if (!obj_index(corner, at, value))
                        throw parse_error({name, line, column}, "a face corner v, v/vt, v//vn or v/vt/vn",
                                          shown_word(corner),
                                          "indices are whole numbers counting from 1 (or back from -1)");
                    if (value < 0 && std::size_t(-value) > counts[kind])
                        throw parse_error({name, line, column},
                                          "a " + std::string(kinds[kind]) + " index of at least -" +
                                              std::to_string(counts[kind]) + " here",
                                          std::to_string(value), "a negative index counts back from the last one read");
                    if (value > largest[kind]) {
                        largest[kind] = value;
                        largest_line[kind] = line;
                    }
                }
                if (at != corner.size())
                    throw parse_error({name, line, column}, "a face corner v, v/vt, v//vn or v/vt/vn",
                                      shown_word(corner));
            }
            const std::size_t corners = words.size() - 1;
            if (corners < 3)
                throw parse_error({name, line}, "a face of at least 3 vertices", "one of " + std::to_string(corners),
                                  "an OBJ face 'f' lists three or more vertex indices");
            triangles += corners - 2;
            if (triangles > limits.max_triangles)
                throw parse_error({name, line}, "at most " + std::to_string(limits.max_triangles) + " triangles",
                                  "more by this face",
                                  "the limit is obj_limits::max_triangles; raise it if you mean it");
        } else if (keyword == "mtllib") {
            // The names as tinyobjloader splits them: at blanks, with '\' escaping one.
            std::vector<std::string> names(1);
            bool escaped = false;
            for (std::size_t i = text.find("mtllib") + 7; i < text.size(); ++i) {
                if (!escaped && text[i] == '\\') {
                    escaped = true;
                    continue;
                }
                if (!escaped && text[i] == ' ')
                    names.emplace_back();
                else
                    names.back() += text[i];
                escaped = false;
            }
            names.erase(std::remove(names.begin(), names.end(), std::string()), names.end());
            if (names.empty())
                throw parse_error({name, line}, "a material library file name after 'mtllib'", "none");
            // tinyobjloader reads the first name that opens, joining the OBJ's
            // folder and the name as text (an absolute name too).
            const std::string folder = path.has_parent_path() ? path.parent_path().string() : std::string(".");
            for (const std::string& library : names) {
                const std::filesystem::path file = folder + "/" + library;
                std::error_code ec;
                if (!std::filesystem::exists(file, ec))
                    continue;
                if (!std::filesystem::is_regular_file(file, ec))
                    throw parse_error({name, line}, "a material library file",
                                      "a folder or special file '" + one_line(library) + "'",
                                      "mtllib names the .mtl file");
                const std::string mtl_name = file.string();
                std::vector<obj_word> mtl_words;
                for_each_obj_line(file, limits, [&](const std::string& mtl_text, int mtl_line) {
                    obj_words(mtl_text, mtl_words);
                    for (std::size_t i = 1; i < mtl_words.size(); ++i)
                        check_obj_number(mtl_words[i].text, mtl_name, mtl_line, int(mtl_words[i].column) + 1, false);
                });
                return;
            }
            throw parse_error({name, line}, "the material library it names",
                              "no such file '" + one_line(names.front()) + "'", "put the .mtl file beside the .obj");
        }
    });
    for (int kind = 0; kind < 3; ++kind)
        if (largest[kind] > 0 && std::size_t(largest[kind]) > counts[kind])
            throw parse_error({name, largest_line[kind]},
                              "a " + std::string(kinds[kind]) + " index between 1 and " + std::to_string(counts[kind]),
                              std::to_string(largest[kind]),
                              "the file has " + std::to_string(counts[kind]) + " of them");
}

inline color to_color(const tinyobj::real_t rgb[3])
{
    return color(float(rgb[0]), float(rgb[1]), float(rgb[2]));
}

} // namespace detail

/// Loads an OBJ file (and the MTL files it names, from its folder).
/// Throws rt::error with file:line for a missing, unreadable or malformed file.
inline obj_result load_obj(const std::filesystem::path& path, const obj_limits& limits = {})
{
    const std::string name = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw error(source_location{name}, "expected an OBJ file, found no such file; check the path");
    if (std::filesystem::is_directory(path, ec))
        throw error(source_location{name}, "expected an OBJ file, found a folder; name the .obj file itself");
    if (!std::filesystem::is_regular_file(path, ec))
        throw error(source_location{name}, "expected an OBJ file, found a device, pipe or socket; name a .obj file");
    if (!std::ifstream(path))
        throw error(source_location{name}, "expected a readable OBJ file, found one that cannot be opened; check its permissions");
    detail::check_obj_text(path, limits);

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    config.mtl_search_path = path.has_parent_path() ? path.parent_path().string() : std::string(".");
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(name, config))
        throw error(source_location{name}, "expected a valid OBJ file, found: " + detail::one_line(reader.Error()));
    const std::string warning = detail::one_line(reader.Warning());
    if (warning.find("not found") != std::string::npos && warning.find("aterial") != std::string::npos)
        throw error(source_location{name},
                    "expected the material library it names, found: " + warning + "; put the .mtl file beside the .obj");

    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    obj_result result;
    mesh& m = result.geometry;
    m.source = name;

    const std::size_t vertex_count = attrib.vertices.size() / 3;
    const std::size_t normal_count = attrib.normals.size() / 3;
    const std::size_t texcoord_count = attrib.texcoords.size() / 2;
    std::size_t total_faces = 0;
    for (const tinyobj::shape_t& group : reader.GetShapes())
        total_faces += group.mesh.num_face_vertices.size();
    if (total_faces > limits.max_triangles)
        throw error(source_location{name}, "expected at most " + std::to_string(limits.max_triangles) +
                                               " triangles, found " + std::to_string(total_faces) +
                                               "; raise obj_limits::max_triangles");

    for (std::size_t i = 0; i < vertex_count; ++i) {
        const vec3 p(real(attrib.vertices[3 * i]), real(attrib.vertices[3 * i + 1]), real(attrib.vertices[3 * i + 2]));
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw error(source_location{name}, "expected finite vertex coordinates, found NaN or inf in vertex " +
                                                   std::to_string(i + 1) + "; fix the file");
        m.positions.push_back(p);
    }
    for (std::size_t i = 0; i < normal_count; ++i)
        m.normals.emplace_back(real(attrib.normals[3 * i]), real(attrib.normals[3 * i + 1]), real(attrib.normals[3 * i + 2]));
    for (std::size_t i = 0; i < texcoord_count; ++i)
        m.texcoords.emplace_back(real(attrib.texcoords[2 * i]), real(attrib.texcoords[2 * i + 1]));

    for (const tinyobj::material_t& source : reader.GetMaterials()) {
        material mat;
        mat.name = source.name;
        mat.ka = detail::to_color(source.ambient);
        mat.kd = detail::to_color(source.diffuse);
        mat.ks = detail::to_color(source.specular);
        mat.p = source.shininess > 0 ? real(source.shininess) : real(1);
        // MTL illumination models 3 and 5 are "reflection on": Ks is the mirror colour.
        mat.km = (source.illum == 3 || source.illum == 5) ? mat.ks : color(0.0f);
        result.materials.push_back(mat);
    }

    bool all_have_normals = normal_count > 0;
    bool all_have_texcoords = texcoord_count > 0;
    bool any_material = false;
    std::vector<int> face_materials;
    std::vector<index3> normal_indices, texcoord_indices;
    std::size_t face_number = 0;
    for (const tinyobj::shape_t& group : reader.GetShapes()) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < group.mesh.num_face_vertices.size(); ++f, ++face_number) {
            const std::size_t corners = group.mesh.num_face_vertices[f];
            if (corners != 3) {
                const source_location where{name, detail::obj_face_line(path, face_number)};
                throw parse_error(where, "a face of at least 3 vertices", "one of " + std::to_string(corners),
                                  "an OBJ face 'f' lists three or more vertex indices");
            }
            index3 position{}, normal{}, texcoord{};
            for (std::size_t k = 0; k < 3; ++k) {
                const tinyobj::index_t& index = group.mesh.indices[offset + k];
                if (index.vertex_index < 0 || std::size_t(index.vertex_index) >= vertex_count) {
                    const source_location where{name, detail::obj_face_line(path, face_number)};
                    throw parse_error(where, "a vertex index between 1 and " + std::to_string(vertex_count),
                                      "an index out of range", "OBJ indices count from 1 ('v' lines above the face)");
                }
                position[k] = std::uint32_t(index.vertex_index);
                if (index.normal_index < 0 || std::size_t(index.normal_index) >= normal_count)
                    all_have_normals = false;
                else
                    normal[k] = std::uint32_t(index.normal_index);
                if (index.texcoord_index < 0 || std::size_t(index.texcoord_index) >= texcoord_count)
                    all_have_texcoords = false;
                else
                    texcoord[k] = std::uint32_t(index.texcoord_index);
            }
            offset += corners;
            const vec3& a = m.positions[position[0]];
            const vec3& b = m.positions[position[1]];
            const vec3& c = m.positions[position[2]];
            const real twice_area = glm::length(glm::cross(b - a, c - a));
            if (!(twice_area > 0)) {
                ++m.dropped_degenerate;
                continue;
            }
            m.triangles.push_back(position);
            normal_indices.push_back(normal);
            texcoord_indices.push_back(texcoord);
            const int material_id = f < group.mesh.material_ids.size() ? group.mesh.material_ids[f] : -1;
            face_materials.push_back(material_id >= 0 && std::size_t(material_id) < result.materials.size() ? material_id : -1);
            any_material = any_material || face_materials.back() >= 0;
        }
    }
    if (all_have_normals)
        m.normal_indices = std::move(normal_indices);
    else
        m.normals.clear();
    if (all_have_texcoords)
        m.texcoord_indices = std::move(texcoord_indices);
    else
        m.texcoords.clear();
    if (any_material)
        m.face_materials = std::move(face_materials);
    return result;
}

} // namespace rt
