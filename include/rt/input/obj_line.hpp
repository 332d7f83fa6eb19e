// obj_line.hpp - one line of an OBJ or MTL file, checked for what tinyobjloader
// cannot read safely (obj_check.hpp, mtl_reader.hpp).
//
// An obj_line is a text_line (text_line.hpp: the words, numbers and error
// messages every reader shares) with the OBJ-specific readers: a face corner
// "v/vt/vn", a tag "t name ints/reals/strings ...", and the number checks that
// keep tinyobjloader (2.0.0rc10), which parses the file after this check, away
// from undefined behaviour (docs/reliability.md, "Decisions").
//
//     rt::detail::for_each_line<rt::detail::obj_line>(text, "a.obj", [&](rt::detail::obj_line& line, int) {
//         if (!line.done() && line.word() == "v")
//             positions.push_back({line.number("the vertex x"), line.number("the vertex y"), line.number("the vertex z")});
//     });
#pragma once

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cmath>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include <tiny_obj_loader.h>

#include "../core/config.hpp"
#include "../core/error.hpp"
#include "text_line.hpp"

namespace rt {
namespace detail {

/// One line of an OBJ or MTL file, read word by word; each reader names what
/// it expects, for the error message.
class obj_line : public text_line {
public:
    obj_line(const std::string& file, const std::vector<line_piece>& pieces, const char* first, const char* last)
        : text_line(file, pieces, first, last) {}
    obj_line(std::string&&, const std::vector<line_piece>&, const char*, const char*) = delete;
    obj_line(const std::string&, std::vector<line_piece>&&, const char*, const char*) = delete;

    /// A finite number, at the precision of rt::real, that tinyobjloader can
    /// read too (check_number_word); `move_on` false: only looks at it.
    real number(const std::string& what, bool move_on = true)
    {
        if (done())
            throw unexpected("a number for " + what);
        check_number_word(what);
        return text_line::number(what, move_on, largest_number());
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
        if (detail::read_number(next_, p, largest_number(), value) == detail::number_reading::too_large) {
            const auto complaint = detail::complain(detail::number_reading::too_large, what, largest_number());
            throw unexpected(complaint.expected, complaint.hint);
        }
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
            throw make_error(at, "a tag with at most " + std::to_string(held) + " value(s), as many as follow",
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
    /// "v/vt/", an empty normal slot after the last '/', is read as "v/vt", as
    /// Blender and trimesh read it: `empty_normal` is that '/' (else null), for
    /// a warning, and so that tinyobjloader, which refuses it, is given "v/vt".
    struct corner {
        long index[3] = {0, 0, 0};
        const char* start[3] = {nullptr, nullptr, nullptr};
        const char* empty_normal = nullptr;
    };

    /// Where `p`, a place in this line, is from the line's start (in the
    /// normalised text the check hands to tinyobjloader).
    std::size_t offset_of(const char* p) const { return std::size_t(p - begin_); }
    std::size_t size() const { return std::size_t(end_ - begin_); }

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
                    throw make_error(at(p), "a whole-number index", "'" + printable(std::string(p, slash), 24) + "'", hint);
                if (c.index[part] == 0)
                    throw make_error(at(p), "an index other than 0 (OBJ counts from 1)",
                                     "'" + printable(std::string(p, slash), 24) + "'", hint);
            } else if (part == 0) {
                throw make_error(at(p), "a vertex index", "'" + printable(std::string(p, stop), 24) + "'", hint);
            } else if (slash == stop && part == 2 && c.index[1] != 0) {
                c.empty_normal = p - 1; // "1/2/": read as "1/2"
                break;
            } else if (slash == stop) {
                // "1/" or "1//": a '/' promises an index after it
                throw make_error(at(p), part == 1 ? "a texture coordinate index after '/'" : "a normal index after the second '/'",
                                 "the end of the corner '" + printable(std::string(next_, stop), 24) + "'", hint);
            }
            if (slash == stop)
                break;
            p = slash + 1;
            if (part == 2)
                throw make_error(at(slash), "at most three indices in a corner", "another '/'", hint);
        }
        next_ = stop;
        skip_blanks();
        return c;
    }
};

} // namespace detail
} // namespace rt
