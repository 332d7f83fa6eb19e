// obj_check.hpp - the line-by-line check of an OBJ file, before tinyobjloader
// parses it (stage 04; obj_loader.hpp says why and what is read).
//
// check_obj reads every line once (obj_line.hpp): it keeps the positions (at
// the precision of rt::real), counts the normals, texture coordinates and
// faces, checks every index and every number, reads the material libraries
// named by mtllib (mtl_reader.hpp), and hands back the text as tinyobjloader
// will read it (normalised). What loading can do without is a warning
// (obj_warnings), or an error with obj_limits::strict.
//
//     rt::obj_limits limits;
//     std::vector<rt::detail::mtl_entry> materials;
//     rt::detail::obj_warnings warnings(limits);
//     std::string normalised;
//     rt::detail::obj_check c = rt::detail::check_obj(text, "a.obj", ".", limits, materials, warnings, normalised);
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "mtl_reader.hpp"
#include "obj_line.hpp"
#include "../system/path_text.hpp"
#include "text_line.hpp"
#include "../core/vec.hpp"

namespace rt {

/// Limits checked before allocating, so a hostile file cannot exhaust memory.
struct obj_limits {
    std::size_t max_triangles = std::size_t(1) << 26;  ///< 67 million
    std::uintmax_t max_bytes = std::uintmax_t(1) << 32; ///< 4 GiB of OBJ text
    /// corners of one face: tinyobjloader's ear clipping takes time in the
    /// square of them, so a one-line face of a million corners would take
    /// hours (docs/architecture.md, "Figures behind the comments")
    std::size_t max_face_corners = 1024;
    /// The largest coordinate magnitude a vertex may have: the intersection
    /// tests multiply coordinate differences (up to 2e18 here), and the
    /// products, summed in twos for the edge functions and cross products
    /// (8e36), must stay below float's largest value (3.4e38); a triangle
    /// 1e19 across is silently missed by every ray (measured: stage04_triangle
    /// hits a triangle 1e18 across, none 1e19 across).
    double max_coordinate = 1e18;
    /// What loading can do without (a missing material library, usemtl
    /// without mtllib, of an unknown name or of none, a face that is not a
    /// simple polygon, a corner "v/vt/" with an empty normal slot) is one
    /// warning line each, or with `strict` (--strict) an error.
    bool strict = false;
    /// Where the warnings go, one line each "file:line:col: warning: ...";
    /// null: std::cerr.
    std::ostream* warnings = nullptr;
};

namespace detail {

/// The warnings of one OBJ file: in strict mode the first is thrown as an
/// error; otherwise each kind is printed once, at its first place, with how
/// many more there were, when the file has loaded (flush).
class obj_warnings {
public:
    enum kind { missing_library, no_library, unknown_material, not_simple, empty_normal, unnamed_material, kinds };

    explicit obj_warnings(const obj_limits& limits) : limits_(limits) {}

    void add(kind k, const source_location& where, const std::string& expected, const std::string& found,
             const std::string& hint)
    {
        if (limits_.strict)
            throw make_error(where, expected, found, hint + " (a warning without --strict)");
        entry& e = entries_[k];
        if (e.count++ == 0) {
            e.message = to_string(where) + ": warning: expected " + expected + ", found " + found;
            e.hint = hint;
            order_.push_back(k);
        }
    }

    std::size_t count(kind k) const { return entries_[k].count; }

    void flush() const
    {
        std::ostream& out = limits_.warnings ? *limits_.warnings : std::cerr;
        for (const kind k : order_) {
            const entry& e = entries_[k];
            out << e.message << (e.count > 1 ? " (and " + std::to_string(e.count - 1) + " more like it)" : "") << "; "
                << e.hint << '\n';
        }
    }

private:
    struct entry {
        std::size_t count = 0;
        std::string message, hint;
    };
    const obj_limits& limits_;
    entry entries_[kinds];
    std::vector<kind> order_;
};

/// What the line-by-line check of an OBJ file found.
struct obj_check {
    std::vector<vec3> positions;
    std::size_t normals = 0, texcoords = 0, polygons = 0, triangles = 0;
    // the largest positive index of each kind and where it was written, checked
    // at the end because a face may refer to elements defined after it
    long largest[3] = {0, 0, 0};
    source_location largest_at[3];
    /// the corners of each face, in file order (tinyobjloader counts them in
    /// an unsigned char), and the line and column of each face of 4 or more
    std::vector<std::uint32_t> face_corners;
    std::vector<std::pair<int, int>> polygon_at; // line, column
    std::vector<std::filesystem::path> libraries; ///< the MTL files opened, for mesh::read_from
};

inline obj_check check_obj(const std::string& text, const std::string& name, const std::filesystem::path& folder,
                           const obj_limits& limits, std::vector<mtl_entry>& materials, obj_warnings& warnings,
                           std::string& normalised)
{
    obj_check out;
    std::vector<std::string> loaded_libraries;
    bool any_library = false, missing_library = false;
    for_each_line<obj_line>(text, name, [&](obj_line& line, int) {
        if (line.done())
            return;
        const source_location keyword_at = line.here();
        const std::string keyword = line.word();
        if (keyword == "v") {
            vec3 p;
            for (int axis = 0; axis < 3; ++axis) {
                const source_location at = line.here();
                p[axis] = line.number(std::string("the vertex ") + "xyz"[axis]);
                if (std::fabs(double(p[axis])) > limits.max_coordinate) {
                    std::ostringstream limit;
                    limit << limits.max_coordinate;
                    throw make_error(at, std::string("a vertex ") + "xyz"[axis] + " within +-" + limit.str(),
                                     "a larger one",
                                     "float arithmetic cannot trace geometry this large; use smaller units "
                                     "(obj_limits::max_coordinate)");
                }
            }
            while (!line.done())
                line.number("a vertex's extra value (w or color)");
            out.positions.push_back(p);
        } else if (keyword == "vn") {
            line.number("the normal x");
            line.number("the normal y");
            line.number("the normal z");
            if (!line.done())
                throw line.unexpected("the end of the line", "a normal has three numbers");
            ++out.normals;
        } else if (keyword == "vt") {
            line.number("the texture coordinate u");
            for (int k = 0; k < 2 && !line.done(); ++k)
                line.number("a texture coordinate");
            if (!line.done())
                throw line.unexpected("the end of the line", "a texture coordinate has at most three numbers");
            ++out.texcoords;
        } else if (keyword == "f" || keyword == "l" || keyword == "p") {
            const std::size_t defined[3] = {out.positions.size(), out.texcoords, out.normals};
            const char* kinds[3] = {"vertex", "texture coordinate", "normal"};
            int corners = 0;
            while (!line.done()) {
                const obj_line::corner c = line.face_corner();
                ++corners;
                if (c.empty_normal) {
                    warnings.add(obj_warnings::empty_normal, line.at(c.empty_normal),
                                 "v/vt/vn or v/vt, a normal index after the second '/'", "nothing after it",
                                 "read as v/vt, as Blender reads it; delete the last '/'");
                    // tinyobjloader refuses "1/2/": it reads this line with "1/2 "
                    normalised[normalised.size() - 1 - line.size() + line.offset_of(c.empty_normal)] = ' ';
                }
                for (int k = 0; k < 3; ++k) {
                    const long index = c.index[k];
                    if (index < 0 && long(defined[k]) + index < 0)
                        throw make_error(line.at(c.start[k]),
                                         std::string("a relative ") + kinds[k] + " index from -1 to -" +
                                             std::to_string(defined[k]),
                                         std::to_string(index),
                                         "a negative index counts back from the latest '" +
                                             std::string(k == 0 ? "v" : k == 1 ? "vt" : "vn") + "' line");
                    if (index > out.largest[k]) {
                        out.largest[k] = index;
                        out.largest_at[k] = line.at(c.start[k]);
                    }
                }
            }
            if (keyword == "f") {
                if (corners < 3)
                    throw make_error(keyword_at, "a face of at least 3 corners", std::to_string(corners),
                                     "'f' lists three or more vertex indices");
                if (std::size_t(corners) > limits.max_face_corners)
                    throw make_error(keyword_at, "a face of at most " + std::to_string(limits.max_face_corners) + " corners",
                                     std::to_string(corners),
                                     "raise obj_limits::max_face_corners (load_options::obj for a scene)");
                ++out.polygons;
                out.triangles += std::size_t(corners - 2);
                out.face_corners.push_back(std::uint32_t(corners));
                if (corners > 3)
                    out.polygon_at.emplace_back(keyword_at.line, keyword_at.column);
                if (out.triangles > limits.max_triangles)
                    throw make_error(keyword_at, "at most " + std::to_string(limits.max_triangles) + " triangles",
                                     "more", "raise obj_limits::max_triangles (load_options::obj for a scene)");
            }
        } else if (keyword == "vw") {
            // tinyobjloader's skin weights "vw vertex joint weight joint weight ...":
            // it reads each joint id as a float and converts it to int, undefined
            // past INT_MAX (C++17 [conv.fpint]/1; UBSan found it with "2147483648"),
            // and fails on a negative one without saying where. rt ignores them.
            line.number("the skin-weight vertex");
            for (int k = 0; !line.at_end(); ++k) {
                if (k % 2 == 0 && !line.done()) {
                    const real value = line.number("a joint id", false);
                    if (!(value >= 0 && value < real(1 << 30)))
                        throw line.unexpected("a joint id from 0 to 2^30", "'vw vertex joint weight ...' names joints by number");
                }
                line.number(k % 2 == 0 ? "a joint id" : "a joint weight");
            }
        } else if (keyword == "t") {
            // tinyobjloader's tags "t name ints/reals/strings value ...": it
            // allocates as many values as the three counts claim (each up to
            // 8192) before it reads them, a third of a megabyte for a line of 20
            // bytes; here a tag claims no more values than its line holds.
            line.check_tag();
        } else if (keyword == "g" || keyword == "o" || keyword == "s") {
            // group and object names, smoothing groups: not used by rt
        } else if (keyword == "mtllib") {
            any_library = true;
            if (line.done())
                throw line.unexpected("a material library file name after mtllib");
            while (!line.done()) {
                const source_location at = line.here();
                const std::string file = line.word();
                // each file once, however spelled ("m.mtl", "./m.mtl", ".//m.mtl"):
                // a file read again would add all its materials again, so a
                // short OBJ line could multiply a large MTL file in memory
                std::error_code ec;
                const std::filesystem::path library = folder / utf8_path(file);
                const std::filesystem::path canonical = std::filesystem::weakly_canonical(library, ec);
                const std::string key = utf8_text(ec ? library.lexically_normal() : canonical);
                if (std::find(loaded_libraries.begin(), loaded_libraries.end(), key) != loaded_libraries.end())
                    continue;
                loaded_libraries.push_back(key);
                std::error_code missing;
                if (!std::filesystem::exists(library, missing) && !missing) {
                    missing_library = true;
                    warnings.add(obj_warnings::missing_library, at, "the material library '" + printable(file, 60) + "'",
                                 "no such file beside the OBJ file",
                                 "its materials are the default material; copy the MTL file beside the OBJ file");
                    continue;
                }
                out.libraries.push_back(library);
                read_mtl(library, at, limits.max_bytes, materials);
            }
        } else if (keyword == "usemtl") {
            if (line.done()) { // tinyobjloader, Blender and trimesh read it as the default material
                warnings.add(obj_warnings::unnamed_material, keyword_at, "a material name after usemtl", "none",
                             "its faces get the default material; name a material or delete the line");
                return;
            }
            const source_location at = line.here();
            const std::string wanted = line.word();
            const bool declared = std::any_of(materials.begin(), materials.end(),
                                              [&](const mtl_entry& m) { return m.value.name == wanted; });
            if (!declared && !any_library) {
                warnings.add(obj_warnings::no_library, at, "a material library ('mtllib') before 'usemtl'",
                             "usemtl '" + printable(wanted, 24) + "' without one",
                             "its faces get the default material; add 'mtllib file.mtl', or delete the usemtl lines");
            } else if (!declared && !missing_library) { // (a missing library was reported already)
                std::string list;
                for (const mtl_entry& m : materials)
                    list += (list.empty() ? "" : ", ") + m.value.name;
                warnings.add(obj_warnings::unknown_material, at, "a material declared in the material library",
                             "'" + printable(wanted, 24) + "'",
                             "its faces get the default material; " +
                                 (list.empty() ? std::string("the library declares none") : "known: " + printable(list, 120)));
            }
        } else {
            // any other statement (curves, surfaces, ...) is not used by rt nor
            // read by tinyobjloader, but its numbers must fit a float too
            line.check_number_words(false);
        }
    }, &normalised);
    const std::size_t counts[3] = {out.positions.size(), out.texcoords, out.normals};
    const char* kinds[3] = {"vertex", "texture coordinate", "normal"};
    const char* lines[3] = {"v", "vt", "vn"};
    for (int k = 0; k < 3; ++k)
        if (out.largest[k] > long(counts[k]))
            throw make_error(out.largest_at[k],
                             std::string("a ") + kinds[k] + " index from 1 to " + std::to_string(counts[k]),
                             std::to_string(out.largest[k]),
                             "the file has " + std::to_string(counts[k]) + " '" + lines[k] + "' lines");
    return out;
}

} // namespace detail
} // namespace rt
