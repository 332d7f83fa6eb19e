// obj_loader.hpp - Wavefront OBJ meshes through tinyobjloader (stage 04).
//
// What is read (the formats of Wavefront's Advanced Visualizer documentation,
// "Object Files (.obj)" and "Material Library Files (.mtl)"):
//   v x y z            a position (extra numbers, such as vertex colours, are allowed and ignored)
//   vn x y z           a normal          vt u [v [w]]   a texture coordinate
//   f v[/vt][/vn] ...  a polygon of 3 or more corners; indices count from 1 in
//                      order of appearance, a negative index counts back from the
//                      latest element (-1 is the last one so far)
//   mtllib a.mtl       material libraries, beside the OBJ file
//   usemtl name        the material of the faces that follow
// and in an MTL file: newmtl name, Ka/Kd/Ks r [g b], Ns exponent, illum model.
// Everything else (groups, smoothing, texture maps, curves) is ignored.
//
// How: the file is read once into memory and checked line by line here, so
// that every problem is one line "file:line:col: expected ..., found ...;
// hint" (tinyobjloader reads a bad number as 0, drops faces with bad indices
// with a warning and does not say where). The positions are taken from this
// check, parsed at the precision of rt::real (Debian's tinyobjloader is built
// with float). tinyobjloader (Debian's libtinyobjloader, linked through rt::rt)
// then parses the faces, with its triangulation off (it split a concave quad
// along its shorter diagonal even when that lies outside, and got 60 of 300
// random simple 5- to 9-gons wrong: tests/library_triangulate.cpp); rt cuts
// each face of 4 or more corners itself (triangulate.hpp). A face that is not
// a simple polygon (edges crossing) is cut as a fan from its first corner with
// a warning; repeated consecutive corners are merged (each counted as a
// dropped degenerate triangle). The MTL files are parsed here and handed to
// tinyobjloader by name, so usemtl picks the same materials in both.
//
// Text: a UTF-8 byte order mark is skipped, lines end at LF, CR LF or CR, and
// a '\' at the end of a line continues it on the next (for_each_line);
// tinyobjloader reads the text so normalised, so the lines it reads are the
// lines checked here and every message keeps the file's line numbers.
//
// What loading can do without is a warning, one line per kind
// "file:line:col: warning: expected ..., found ... (and N more like it); hint"
// on obj_limits::warnings (std::cerr), and an error with obj_limits::strict
// (the programs' --strict): a material library that does not exist (its
// materials: the default material), usemtl without mtllib or of a name no
// library declares (the default material), a face that is not simple.
//
// The check also keeps tinyobjloader (2.0.0rc10) away from what it cannot
// read safely (docs/reliability.md, "Decisions"): every number, also in the
// statements rt ignores, must fit a float, with an exponent from -400 to 400
// and at most 300 digits; a skin-weight joint id ("vw") must be from 0 to
// 2^30; a tag ("t") may claim no more values than its line holds; a face has
// at most obj_limits::max_face_corners corners; an MTL file is read once
// however it is spelled. A coordinate must be within +-obj_limits::max_coordinate
// (1e18), beyond which float arithmetic cannot trace a triangle.
//
// The mesh stores only what the file provides: normals (texture coordinates)
// only when the faces refer to them. Zero-area triangles are dropped and
// counted in mesh::dropped_degenerate. MTL colours map to rt::material: Ka ka
// (kd when absent, as in scene files), Kd kd, Ks ks, Ns p, and for the
// illumination models "reflection on, ray trace on" (illum 3 and 5) km = Ks.
// Names (newmtl, usemtl) are one word, as tinyobjloader reads them.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <streambuf>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <tiny_obj_loader.h>

#include "error.hpp"
#include "material.hpp"
#include "mesh.hpp"
#include "triangulate.hpp"

namespace rt {

/// What loading an OBJ file gives: the mesh and the materials of its MTL files
/// (mesh::face_materials index into `materials`).
struct obj_result {
    mesh geometry;
    std::vector<material> materials;
    std::size_t polygons = 0;  ///< face statements in the file (before triangulation)
};

/// Limits checked before allocating, so a hostile file cannot exhaust memory.
struct obj_limits {
    std::size_t max_triangles = std::size_t(1) << 26;  ///< 67 million
    std::uintmax_t max_bytes = std::uintmax_t(1) << 32; ///< 4 GiB of OBJ text
    /// corners of one face: tinyobjloader's ear clipping takes time in the
    /// square of them (measured: 7 ms for 1000, 0.14 s for 4000, so a
    /// one-line face of a million corners would take hours)
    std::size_t max_face_corners = 1024;
    /// The largest coordinate magnitude a vertex may have: the intersection
    /// tests multiply coordinate differences (up to 2e18 here), and the
    /// products, summed in twos for the edge functions and cross products
    /// (8e36), must stay below float's largest value (3.4e38); a triangle
    /// 1e19 across is silently missed by every ray (measured: stage04_triangle
    /// hits a triangle 1e18 across, none 1e19 across).
    double max_coordinate = 1e18;
    /// What loading can do without (a missing material library, usemtl
    /// without mtllib or of an unknown name, a face that is not a simple
    /// polygon) is one warning line each, or with `strict` (--strict) an error.
    bool strict = false;
    /// Where the warnings go, one line each "file:line:col: warning: ...";
    /// null: std::cerr.
    std::ostream* warnings = nullptr;
};

namespace detail {

/// Where a piece of a logical line starts: a line continued with '\\' at its
/// end (OBJ and MTL files) is read as one line made of several pieces.
struct line_piece {
    std::size_t offset = 0; ///< in the logical line
    int line = 0;           ///< in the file, from 1
    int column = 1;         ///< of the piece's first character, from 1
};

/// One line of an OBJ or MTL file, read word by word; each reader names what
/// it expects, for the error message.
class obj_line {
public:
    obj_line(const std::string& file, const std::vector<line_piece>& pieces, const char* first, const char* last)
        : file_(file), pieces_(pieces), begin_(first), next_(first), end_(last)
    {
        skip_blanks();
    }

    bool done() const { return next_ == end_ || *next_ == '#'; }
    source_location here() const { return at(next_); }
    /// The file's line and column of a character of this line.
    source_location at(const char* position) const
    {
        const std::size_t offset = std::size_t(position - begin_);
        std::size_t k = pieces_.size() - 1;
        while (k > 0 && pieces_[k].offset > offset)
            --k;
        return {file_, pieces_[k].line, pieces_[k].column + int(offset - pieces_[k].offset)};
    }

    std::string word()
    {
        const char* start = next_;
        while (next_ != end_ && *next_ != ' ' && *next_ != '\t')
            ++next_;
        std::string text(start, next_);
        skip_blanks();
        return text;
    }

    error unexpected(const std::string& expected, const std::string& hint = {}) const
    {
        return parse_error(here(), expected, done() ? "the end of the line" : "'" + printable(peek_word(), 24) + "'", hint);
    }

    /// A finite number, at the precision of rt::real (see check_number_word);
    /// `move_on` false: only looks at it.
    real number(const std::string& what, bool move_on = true)
    {
        if (done())
            throw unexpected("a number for " + what);
        check_number_word(what);
        const char* start = next_;
        if (*start == '+')
            ++start;
        const char* stop = start;
        while (stop != end_ && *stop != ' ' && *stop != '\t')
            ++stop;
        double value = 0;
        const auto [end, status] = std::from_chars(start, stop, value);
        if (status == std::errc() && end == stop && !std::isfinite(value))
            throw unexpected("a finite number for " + what, "NaN and inf are not allowed");
        if ((status != std::errc() && status != std::errc::result_out_of_range) || end != stop)
            throw unexpected("a number for " + what);
        if (move_on) {
            next_ = stop;
            skip_blanks();
        }
        // check_number_word refused every overflow, so an out-of-range result is
        // an underflow: a magnitude below the smallest double, 0 at any precision
        return status == std::errc() ? real(value) : real(0);
    }

    /// Checks the number the next word starts with, if it starts like one for
    /// tinyobjloader's tryParseDouble ([+-], then a digit or '.'), and does not
    /// move on. tinyobjloader reads such a prefix of any word it takes for a
    /// number (coordinates, skin weights, tag values) in three steps that go
    /// wrong on numbers no float holds anyway, so those are refused here first:
    ///  - it adds up the exponent's digits in an int, which overflows past
    ///    2147483647 (undefined behaviour, C++17 [expr]/4; UBSan found it with
    ///    "0e2147483648"): the exponent must be from -400 to 400;
    ///  - it adds up the mantissa's digits in a double, inf past 308 digits:
    ///    the mantissa must be at most 300 characters;
    ///  - it converts the double to float, undefined beyond float's range
    ///    (C++17 [conv.double]/1): the magnitude must be at most the largest
    ///    rt::real (about 3.4e38 for float). A smaller magnitude than the
    ///    smallest float is no error: it rounds to 0 (or a subnormal).
    /// `what` ("the vertex x", or empty) says what the number is for.
    /// `prefix`: check a word that only starts like a number too ("1e999x"),
    /// as tinyobjloader reads it; otherwise only a word that is one number
    /// (not a file name such as "1e999.png").
    void check_number_word(const std::string& what, bool prefix = true) const
    {
        const auto digit = [&](const char* at) { return at != end_ && *at >= '0' && *at <= '9'; };
        const char* p = next_;
        if (p != end_ && (*p == '+' || *p == '-'))
            ++p;
        if (!(digit(p) || (p != end_ && *p == '.')))
            return; // not a number to tinyobjloader; the callers say what they expected
        const char* mantissa = p;
        while (digit(p))
            ++p;
        if (p != end_ && *p == '.')
            for (++p; digit(p); ++p) {
            }
        const char* const mantissa_end = p;
        long exponent = 0;
        if (p != end_ && (*p == 'e' || *p == 'E')) {
            ++p;
            if (p != end_ && (*p == '+' || *p == '-'))
                ++p;
            for (; digit(p); ++p)
                exponent = std::min(exponent * 10 + (*p - '0'), 100000L);
        }
        if (!prefix && p != end_ && *p != ' ' && *p != '\t')
            return;
        const auto a_number = [&] { return what.empty() ? std::string("a number") : "a number for " + what; };
        if (mantissa_end - mantissa > 300)
            throw unexpected(a_number() + " of at most 300 digits", "write it shorter, with an exponent");
        if (exponent > 400)
            throw unexpected(a_number() + " with an exponent from -400 to 400",
                             "no float needs more; tinyobjloader cannot read a longer exponent");
        double value = 0;
        const char* first = next_ != end_ && *next_ == '+' ? next_ + 1 : next_;
        const auto [end, status] = std::from_chars(first, p, value);
        const bool overflow = status == std::errc::result_out_of_range && p != mantissa_end &&
                              std::find(mantissa_end, p, '-') == p; // out of range with a positive exponent
        if (overflow || (status == std::errc() && std::fabs(value) > largest_number())) {
            std::ostringstream limit;
            limit << largest_number();
            throw unexpected(a_number() + " within +-" + limit.str(), "use smaller units");
        }
        (void)end;
    }

    /// Checks every word left on the line that is a number, or with `prefix`
    /// starts like one (see check_number_word), comments included:
    /// tinyobjloader does not stop at a '#' after the first word.
    void check_number_words(bool prefix)
    {
        while (next_ != end_) {
            check_number_word("", prefix);
            word();
        }
    }

    bool at_end() const { return next_ == end_; }

    /// The rest of an OBJ tag line "t name ints/reals/strings value ...":
    /// the three counts, read as tinyobjloader's parseTagTriple reads them
    /// (atoi of each part, clamped to 0..8192), may claim no more values than
    /// there are words after them; the values that are numbers are checked.
    void check_tag()
    {
        word(); // the tag's name
        const source_location at = here();
        const char* p = next_;
        long claimed = 0;
        for (int part = 0; part < 3; ++part) {
            // atoi: blanks, a sign, digits (saturated here)
            while (p != end_ && (*p == ' ' || *p == '\t'))
                ++p;
            const bool negative = p != end_ && *p == '-';
            if (p != end_ && (*p == '+' || *p == '-'))
                ++p;
            long count = 0;
            for (; p != end_ && *p >= '0' && *p <= '9'; ++p)
                count = std::min(count * 10 + (*p - '0'), 8192L);
            claimed += negative ? 0 : count;
            while (p != end_ && (part == 2 || *p != '/') && *p != ' ' && *p != '\t')
                ++p;
            if (p == end_ || *p != '/')
                break;
            ++p;
        }
        next_ = p;
        skip_blanks();
        long held = 0;
        for (const char* q = next_; q != end_;) {
            ++held;
            while (q != end_ && *q != ' ' && *q != '\t')
                ++q;
            while (q != end_ && (*q == ' ' || *q == '\t'))
                ++q;
        }
        if (claimed > held)
            throw parse_error(at, "a tag with at most " + std::to_string(held) + " value(s), as many as follow",
                              "one that claims " + std::to_string(claimed),
                              "'t name ints/reals/strings value ...' counts the values on its line");
        check_number_words(true);
    }

    /// The largest magnitude both rt::real and tinyobjloader's real_t hold.
    static double largest_number()
    {
        return std::min(double(std::numeric_limits<real>::max()), double(std::numeric_limits<tinyobj::real_t>::max()));
    }

    bool number_follows() const
    {
        if (done())
            return false;
        const char c = *next_;
        return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
    }

    /// One face corner "v", "v/vt", "v//vn" or "v/vt/vn": three indices as
    /// written (0: absent) and where each starts in the line (for at()).
    struct corner {
        long index[3] = {0, 0, 0};
        const char* start[3] = {nullptr, nullptr, nullptr};
    };

    corner face_corner()
    {
        corner c;
        const char* stop = next_;
        while (stop != end_ && *stop != ' ' && *stop != '\t')
            ++stop;
        const std::string hint = "a corner is v, v/vt, v//vn or v/vt/vn";
        const char* p = next_;
        for (int part = 0; part < 3; ++part) {
            c.start[part] = p;
            const char* slash = p;
            while (slash != stop && *slash != '/')
                ++slash;
            if (slash != p) {
                const auto [end, status] = std::from_chars(p, slash, c.index[part]);
                if (status != std::errc() || end != slash)
                    throw parse_error(at(p), "a whole-number index", "'" + printable(std::string(p, slash), 24) + "'", hint);
                if (c.index[part] == 0)
                    throw parse_error(at(p), "an index other than 0 (OBJ counts from 1)",
                                      "'" + printable(std::string(p, slash), 24) + "'", hint);
            } else if (part == 0) {
                throw parse_error(at(p), "a vertex index", "'" + printable(std::string(p, stop), 24) + "'", hint);
            } else if (slash == stop) {
                // "1/" or "1//" or "1/2/": a '/' promises an index after it
                throw parse_error(at(p), part == 1 ? "a texture coordinate index after '/'" : "a normal index after the second '/'",
                                  "the end of the corner '" + printable(std::string(next_, stop), 24) + "'", hint);
            }
            if (slash == stop)
                break;
            p = slash + 1;
            if (part == 2)
                throw parse_error(at(slash), "at most three indices in a corner", "another '/'", hint);
        }
        next_ = stop;
        skip_blanks();
        return c;
    }

private:
    void skip_blanks()
    {
        while (next_ != end_ && (*next_ == ' ' || *next_ == '\t'))
            ++next_;
    }

    std::string peek_word() const
    {
        const char* stop = next_;
        while (stop != end_ && *stop != ' ' && *stop != '\t' && stop - next_ < 24)
            ++stop;
        std::string shown;
        for (const char* p = next_; p != stop; ++p)
            shown += (*p >= 32 && *p < 127) ? *p : '?';
        return shown;
    }

    const std::string& file_;
    const std::vector<line_piece>& pieces_;
    const char* begin_;
    const char* next_;
    const char* end_;
};

/// Calls `each(line, number)` for every line of `text` (without the end of
/// line; `number` is the file's line where it starts), after checking that it
/// is text. Every file is read alike (OBJ, MTL, and scene files in
/// scene_loader.hpp): a UTF-8 byte order mark at the start is skipped (the
/// first column is the character after it); a line ends at LF, CR LF or a lone
/// CR (classic Mac OS files); and, in OBJ and MTL files, a '\\' that ends a
/// line joins the next line to it, read as a blank (the OBJ specification,
/// "Object Files (.obj)": "long lines can be continued with a backslash").
/// `normalised`, when given, receives the lines as read: each logical line
/// once, ended by LF, for tinyobjloader, which then reads the same lines.
template <class Each>
void for_each_line(const std::string& text, const std::string& file, Each&& each, std::string* normalised = nullptr)
{
    const char* p = text.data();
    const char* const end = p + text.size();
    if (text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0)
        p += 3;
    int number = 0;
    std::string logical;
    std::vector<line_piece> pieces;
    while (p != end) {
        logical.clear();
        pieces.clear();
        const int first = number + 1;
        for (;;) {
            if (number == std::numeric_limits<int>::max())
                throw error(source_location{file, number}, "expected at most " + std::to_string(number) +
                                                               " lines, found more; split the file");
            ++number;
            const char* stop = p;
            while (stop != end && *stop != '\n' && *stop != '\r') {
                const unsigned char c = static_cast<unsigned char>(*stop);
                if (c < 32 && c != '\t')
                    throw parse_error({file, number, int(stop - p) + 1}, "text",
                                      "a byte of value " + std::to_string(int(c)), "is this an OBJ or MTL file?");
                ++stop;
            }
            pieces.push_back({logical.size(), number, 1});
            logical.append(p, stop);
            const bool continued = stop != p && stop[-1] == '\\' && stop != end;
            if (stop != end && *stop == '\r' && stop + 1 != end && stop[1] == '\n')
                ++stop; // CR LF is one line break
            p = stop == end ? end : stop + 1;
            if (!continued || p == end)
                break;
            logical.back() = ' '; // the backslash joins the lines like a blank
        }
        if (normalised) {
            normalised->append(logical);
            normalised->push_back('\n');
        }
        obj_line line(file, pieces, logical.data(), logical.data() + logical.size());
        each(line, first);
    }
}

inline std::string read_text(const std::filesystem::path& path, const std::string& what, std::uintmax_t max_bytes,
                             const source_location& named_at)
{
    const std::string name = printable(path.string());
    std::error_code ec;
    const source_location at = named_at.file.empty() ? source_location{name} : named_at;
    if (std::filesystem::is_directory(path, ec))
        throw error(at, "expected " + what + " file, found a folder '" + name + "'; name the file itself");
    if (!std::filesystem::exists(path, ec))
        throw error(at, "expected " + what + " file, found no such file '" + name + "'; check the path");
    // a device, pipe or socket could block or never end (/dev/zero): read regular files only
    if (!std::filesystem::is_regular_file(path, ec))
        throw error(at, "expected " + what + " file, found a device, pipe or socket '" + name +
                            "'; name a regular file");
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec && size > max_bytes)
        throw error(at, "expected " + what + " file of at most " + std::to_string(max_bytes) + " bytes, found " +
                            std::to_string(size) + "; raise obj_limits::max_bytes (load_options::obj for a scene)");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw error(at, "expected " + what + " file that can be read, found one that cannot be opened: '" + name +
                            "'; check its permissions");
    std::string text;
    if (!ec)
        text.reserve(std::size_t(size));
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad())
        throw error(at, "reading failed; is the file complete?");
    return text;
}

/// One MTL material as read here, with what tinyobjloader would not tell: which
/// statements were present.
struct mtl_entry {
    material value;
    bool has_ka = false;
    bool has_ns = false;
    int illum = 2;
};

/// Parses one MTL file into `entries` (see the top of this file).
inline void read_mtl(const std::filesystem::path& path, const source_location& named_at, std::uintmax_t max_bytes,
                     std::vector<mtl_entry>& entries)
{
    const std::string name = path.string();
    const std::string text = read_text(path, "the material library", max_bytes, named_at);
    for_each_line(text, name, [&](obj_line& line, int) {
        if (line.done())
            return;
        const source_location keyword_at = line.here();
        const std::string keyword = line.word();
        if (keyword == "newmtl") {
            if (line.done())
                throw line.unexpected("a material name after newmtl");
            mtl_entry entry;
            entry.value.name = line.word();
            entries.push_back(entry);
            return;
        }
        const bool colour = keyword == "Ka" || keyword == "Kd" || keyword == "Ks";
        const bool known = colour || keyword == "Ns" || keyword == "illum";
        if (!known) { // Ke, Ni, d, Tr, maps ...: not used by rt, but their numbers must fit a float too
            line.check_number_words(false);
            return;
        }
        if (entries.empty())
            throw parse_error(keyword_at, "'newmtl name' before '" + printable(keyword, 24) + "'", "'" + printable(keyword, 24) + "' first",
                              "every material starts with newmtl");
        mtl_entry& entry = entries.back();
        if (colour) {
            if (!line.done() && !line.number_follows())
                throw line.unexpected("an RGB colour for " + keyword, "rt reads 'K? r g b' (not spectral or xyz)");
            color c;
            for (int channel = 0; channel < 3; ++channel) {
                if (channel == 1 && line.done()) { // "Kd r" means r r r
                    c.g = c.b = c.r;
                    break;
                }
                const source_location at = line.here();
                const real value = line.number(keyword + " " + "rgb"[channel]);
                if (value < 0)
                    throw parse_error(at, "a non-negative " + keyword, std::to_string(value),
                                      "colours cannot be negative");
                c[channel] = float(value);
            }
            if (keyword == "Ka") {
                entry.value.ka = c;
                entry.has_ka = true;
            } else if (keyword == "Kd") {
                entry.value.kd = c;
            } else {
                entry.value.ks = c;
            }
        } else if (keyword == "Ns") {
            const source_location at = line.here();
            entry.value.p = line.number("the Phong exponent Ns");
            if (entry.value.p < 0)
                throw parse_error(at, "a non-negative Ns", std::to_string(entry.value.p));
            entry.has_ns = true;
        } else {
            const source_location at = line.here();
            const real model = line.number("the illumination model");
            if (!(model >= 0 && model <= 10 && model == std::floor(model)))
                throw parse_error(at, "an illumination model 0 to 10", std::to_string(model));
            entry.illum = int(model);
        }
        if (!line.done())
            throw line.unexpected("the end of the line", "'" + keyword + "' takes fewer numbers");
    });
}

/// Hands the MTL materials read above to tinyobjloader by name, so that its
/// material ids index `entries` (it then never parses an MTL file itself).
class mtl_names_reader : public tinyobj::MaterialReader {
public:
    explicit mtl_names_reader(const std::vector<mtl_entry>& entries) : entries_(entries) {}

    bool operator()(const std::string&, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string*, std::string*) override
    {
        if (done_)
            return true;
        done_ = true;
        for (const mtl_entry& entry : entries_) {
            tinyobj::material_t m{}; // value-initialised: its plain fields are zero, not indeterminate
            m.name = entry.value.name;
            if (names->count(m.name) == 0) // the first material of a name wins, as in the check
                (*names)[m.name] = int(materials->size());
            materials->push_back(m);
        }
        return true;
    }

private:
    const std::vector<mtl_entry>& entries_;
    bool done_ = false;
};

/// A read-only stream over text already in memory.
class memory_buffer : public std::streambuf {
public:
    explicit memory_buffer(std::string& text) { setg(text.data(), text.data(), text.data() + text.size()); }
};

/// The warnings of one OBJ file: in strict mode the first is thrown as an
/// error; otherwise each kind is printed once, at its first place, with how
/// many more there were, when the file has loaded (flush).
class obj_warnings {
public:
    enum kind { missing_library, no_library, unknown_material, not_simple, kinds };

    explicit obj_warnings(const obj_limits& limits) : limits_(limits) {}

    void add(kind k, const source_location& where, const std::string& expected, const std::string& found,
             const std::string& hint)
    {
        if (limits_.strict)
            throw parse_error(where, expected, found, hint + " (a warning without --strict)");
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
    for_each_line(text, name, [&](obj_line& line, int) {
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
                    throw parse_error(at, std::string("a vertex ") + "xyz"[axis] + " within +-" + limit.str(),
                                      "a larger one",
                                      "float arithmetic cannot trace geometry this large; use smaller units "
                                      "(obj_limits::max_coordinate)");
                }
            }
            while (!line.done())
                line.number("a vertex's extra value (w or colour)");
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
                for (int k = 0; k < 3; ++k) {
                    const long index = c.index[k];
                    if (index < 0 && long(defined[k]) + index < 0)
                        throw parse_error(line.at(c.start[k]),
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
                    throw parse_error(keyword_at, "a face of at least 3 corners", std::to_string(corners),
                                      "'f' lists three or more vertex indices");
                if (std::size_t(corners) > limits.max_face_corners)
                    throw parse_error(keyword_at, "a face of at most " + std::to_string(limits.max_face_corners) + " corners",
                                      std::to_string(corners),
                                      "raise obj_limits::max_face_corners (load_options::obj for a scene)");
                ++out.polygons;
                out.triangles += std::size_t(corners - 2);
                out.face_corners.push_back(std::uint32_t(corners));
                if (corners > 3)
                    out.polygon_at.emplace_back(keyword_at.line, keyword_at.column);
                if (out.triangles > limits.max_triangles)
                    throw parse_error(keyword_at, "at most " + std::to_string(limits.max_triangles) + " triangles",
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
                const std::filesystem::path canonical = std::filesystem::weakly_canonical(folder / file, ec);
                const std::string key = ec ? (folder / file).lexically_normal().string() : canonical.string();
                if (std::find(loaded_libraries.begin(), loaded_libraries.end(), key) != loaded_libraries.end())
                    continue;
                loaded_libraries.push_back(key);
                std::error_code missing;
                if (!std::filesystem::exists(folder / file, missing) && !missing) {
                    missing_library = true;
                    warnings.add(obj_warnings::missing_library, at, "the material library '" + printable(file, 60) + "'",
                                 "no such file beside the OBJ file",
                                 "its materials are the default material; copy the MTL file beside the OBJ file");
                    continue;
                }
                out.libraries.push_back(folder / file);
                read_mtl(folder / file, at, limits.max_bytes, materials);
            }
        } else if (keyword == "usemtl") {
            if (line.done())
                throw line.unexpected("a material name after usemtl");
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
            throw parse_error(out.largest_at[k],
                              std::string("a ") + kinds[k] + " index from 1 to " + std::to_string(counts[k]),
                              std::to_string(out.largest[k]),
                              "the file has " + std::to_string(counts[k]) + " '" + lines[k] + "' lines");
    return out;
}

} // namespace detail

/// Loads an OBJ file (and the MTL files it names, from its folder). Throws
/// rt::error with file:line:col for a missing, unreadable or malformed file.
inline obj_result load_obj(const std::filesystem::path& path, const obj_limits& limits = {})
{
    const std::string name = path.string();
    const std::string text = detail::read_text(path, "an OBJ", limits.max_bytes, {});
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    std::vector<detail::mtl_entry> mtl;
    detail::obj_warnings warnings(limits);
    // tinyobjloader reads the lines as the check read them: without a byte
    // order mark, line breaks made LF, continued lines joined
    std::string normalised;
    detail::obj_check checked = detail::check_obj(text, name, folder, limits, mtl, warnings, normalised);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> groups;
    std::vector<tinyobj::material_t> tiny_materials;
    std::string warning, failure;
    detail::memory_buffer buffer(normalised);
    std::istream stream(&buffer);
    detail::mtl_names_reader names(mtl);
    // triangulate = false: tinyobjloader only parses; rt triangulates (triangulate.hpp)
    if (!tinyobj::LoadObj(&attrib, &groups, &tiny_materials, &warning, &failure, &stream, &names, false, false)) {
        // not reached after the check above (which refuses all that tinyobjloader
        // does); its own text has no place and may be wrong, so it is not shown
        throw error(source_location{name}, "expected an OBJ file tinyobjloader can read, found one it refuses "
                                           "though rt's check passed it; please report this file");
    }

    obj_result result;
    result.polygons = checked.polygons;
    mesh& m = result.geometry;
    m.source = name;
    m.read_from.push_back(path);
    m.read_from.insert(m.read_from.end(), checked.libraries.begin(), checked.libraries.end());
    m.positions = std::move(checked.positions);
    for (const detail::mtl_entry& entry : mtl) {
        material mat = entry.value;
        if (!entry.has_ka)
            mat.ka = mat.kd; // as in scene files
        if (!entry.has_ns)
            mat.p = material{}.p;
        mat.km = (entry.illum == 3 || entry.illum == 5) ? mat.ks : color(0.0f); // reflection on
        result.materials.push_back(mat);
    }

    const std::size_t normal_count = attrib.normals.size() / 3;
    const std::size_t texcoord_count = attrib.texcoords.size() / 2;
    const std::size_t vertex_count = m.positions.size();
    bool any_normal = false, any_texcoord = false, any_material = false;
    std::vector<index3> normal_indices, texcoord_indices;
    std::vector<int> face_materials;
    std::size_t face_number = 0, polygon_number = 0;
    std::vector<vec3> polygon;
    std::vector<corner3> pieces;
    for (const tinyobj::shape_t& group : groups) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < group.mesh.num_face_vertices.size(); ++f) {
            // the corner count from the check: tinyobjloader keeps it in an unsigned char
            const std::size_t corners =
                face_number < checked.face_corners.size() ? checked.face_corners[face_number++] : 0;
            if (corners % 256 != group.mesh.num_face_vertices[f] || offset + corners > group.mesh.indices.size())
                throw error(source_location{name}, "expected the faces rt's check counted, found others in "
                                                   "tinyobjloader's result; please report this file");
            const std::size_t first = offset;
            offset += corners;
            pieces.clear();
            if (corners == 3) {
                pieces.push_back({0, 1, 2});
            } else {
                polygon.clear();
                bool inside = true;
                for (std::size_t k = 0; k < corners; ++k) {
                    const int index = group.mesh.indices[first + k].vertex_index;
                    inside = inside && index >= 0 && std::size_t(index) < vertex_count;
                    polygon.push_back(inside ? m.positions[std::size_t(index)] : vec3(0));
                }
                const source_location at =
                    polygon_number < checked.polygon_at.size()
                        ? source_location{name, checked.polygon_at[polygon_number].first,
                                          checked.polygon_at[polygon_number].second}
                        : source_location{name};
                ++polygon_number;
                if (!inside) // cannot happen after the check above; never index out of range
                    continue;
                polygon_triangulation cut = triangulate_polygon(polygon);
                if (cut.problem == polygon_problem::not_simple)
                    warnings.add(detail::obj_warnings::not_simple, at, "a simple polygon",
                                 "a face of " + std::to_string(corners) + " corners with " + to_string(cut.problem),
                                 "it is cut into a fan from its first corner; check the face in a modelling program");
                m.dropped_degenerate += corners - 2 - cut.triangles.size(); // repeated corners merged
                pieces = std::move(cut.triangles);
            }
            for (const corner3& piece : pieces) {
                index3 position{}, normal{}, texcoord{};
                bool valid = true;
                for (std::size_t k = 0; k < 3; ++k) {
                    const tinyobj::index_t& index = group.mesh.indices[first + piece[k]];
                    valid = valid && index.vertex_index >= 0 && std::size_t(index.vertex_index) < vertex_count;
                    position[k] = std::uint32_t(index.vertex_index);
                    const bool has_normal = index.normal_index >= 0 && std::size_t(index.normal_index) < normal_count;
                    const bool has_texcoord =
                        index.texcoord_index >= 0 && std::size_t(index.texcoord_index) < texcoord_count;
                    normal[k] = has_normal ? std::uint32_t(index.normal_index) : no_index;
                    texcoord[k] = has_texcoord ? std::uint32_t(index.texcoord_index) : no_index;
                }
                if (!valid) // cannot happen after the check above; never index out of range
                    continue;
                const vec3& a = m.positions[position[0]];
                const vec3& b = m.positions[position[1]];
                const vec3& c = m.positions[position[2]];
                if (!(glm::length(glm::cross(b - a, c - a)) > 0)) {
                    ++m.dropped_degenerate;
                    continue;
                }
                m.triangles.push_back(position);
                normal_indices.push_back(normal);
                texcoord_indices.push_back(texcoord);
                any_normal = any_normal || normal[0] != no_index || normal[1] != no_index || normal[2] != no_index;
                any_texcoord =
                    any_texcoord || texcoord[0] != no_index || texcoord[1] != no_index || texcoord[2] != no_index;
                const int id = f < group.mesh.material_ids.size() ? group.mesh.material_ids[f] : -1;
                face_materials.push_back(id >= 0 && std::size_t(id) < result.materials.size() ? id : -1);
                any_material = any_material || face_materials.back() >= 0;
            }
        }
    }
    warnings.flush();
    if (any_normal) {
        m.normals.reserve(normal_count);
        for (std::size_t i = 0; i < normal_count; ++i)
            m.normals.emplace_back(real(attrib.normals[3 * i]), real(attrib.normals[3 * i + 1]),
                                   real(attrib.normals[3 * i + 2]));
        m.normal_indices = std::move(normal_indices);
    }
    if (any_texcoord) {
        m.texcoords.reserve(texcoord_count);
        for (std::size_t i = 0; i < texcoord_count; ++i)
            m.texcoords.emplace_back(real(attrib.texcoords[2 * i]), real(attrib.texcoords[2 * i + 1]));
        m.texcoord_indices = std::move(texcoord_indices);
    }
    if (any_material)
        m.face_materials = std::move(face_materials);
    return result;
}

/// Requires that a loaded OBJ file has a triangle to trace: the one message of
/// every program that renders a bare OBJ file (a file of comments only, or of
/// zero-area faces only, would give a black image).
inline void require_triangles(const obj_result& loaded)
{
    const mesh& m = loaded.geometry;
    if (!m.triangles.empty())
        return;
    throw error(source_location{m.source},
                "expected a model with at least one triangle, found " +
                    (m.dropped_degenerate > 0
                         ? "only " + std::to_string(m.dropped_degenerate) + " degenerate (zero-area) triangle(s)"
                         : std::string("no faces")) +
                    "; check the OBJ file");
}

/// One line describing a loaded OBJ file, for a program to print.
inline std::string summary(const obj_result& loaded)
{
    const mesh& m = loaded.geometry;
    std::ostringstream out;
    out << m.source << ": " << m.triangles.size() << " triangles from " << loaded.polygons << " faces, "
        << m.positions.size() << " vertices, " << (m.normals.empty() ? "no" : std::to_string(m.normals.size()))
        << " normals, " << (m.texcoords.empty() ? "no" : std::to_string(m.texcoords.size()))
        << " texture coordinates, " << loaded.materials.size() << " materials, " << m.dropped_degenerate
        << " degenerate triangles dropped";
    return out.str();
}

} // namespace rt
