// text_file.hpp - a text file, a line at a time: scene, OBJ and MTL files alike.
//
// Every file rt reads is text: read_text reads a whole regular file (OBJ, MTL)
// and for_each_line hands out its lines; read_bounded_line reads a stream a
// line at a time (scene files). A line ends at LF, CR LF or a lone CR (classic
// Mac OS files), so line numbers are right whichever a file uses, and a UTF-8
// byte order mark at the start is skipped. text_line.hpp reads the words of a line.
//
//     const std::string text = rt::detail::read_text("a.obj", "an OBJ", max_bytes, {});
//     rt::detail::for_each_line<rt::text_line>(text, "a.obj", [&](rt::text_line& line, int number) { ... });
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <istream>
#include <iterator>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

#include "../core/error.hpp"
#include "../system/path_text.hpp"

namespace rt {

/// Where a piece of a logical line starts: a line continued with '\\' at its
/// end (OBJ and MTL files) is read as one line made of several pieces.
struct line_piece {
    std::size_t offset = 0; ///< in the logical line
    int line = 0;           ///< in the file, from 1
    int column = 1;         ///< of the piece's first character, from 1
};

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
            throw make_error({where.file, where.line, int(i) + 1}, "plain text (ASCII or UTF-8)",
                             "a byte of value " + std::to_string(int(c)), "is this a scene file?");
        i += length;
    }
}

/// Reads the next line of `in` into `text`, without its line break, but never
/// more than `limit` + 1 characters, so that a file without line breaks cannot
/// exhaust memory (the caller rejects a line longer than `limit`). Returns
/// false at the end of the input, as std::getline does.
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

/// Calls `each(line, number)` for every line of `text`, a whole OBJ or MTL file
/// (`line` a Line over it without the end of line, `number` the file's line
/// where it starts), after checking that it is text: a UTF-8 byte order mark at
/// the start is skipped (the first column is the character after it), and a
/// '\\' that ends a line joins the next line to it, read as a blank (the OBJ
/// specification, "Object Files (.obj)": "long lines can be continued with a
/// backslash"). `normalised`, when given, receives the lines as read: each
/// logical line once, ended by LF, for tinyobjloader, which then reads the same lines.
template <class Line, class Each>
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
                    throw make_error({file, number, int(stop - p) + 1}, "text",
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
        Line line(file, pieces, logical.data(), logical.data() + logical.size());
        each(line, first);
    }
}

/// Reads a whole regular file of at most `max_bytes` into memory; `what` ("an
/// OBJ") names it in messages, at `named_at` (where a scene or OBJ file names
/// it) or at the file itself.
inline std::string read_text(const std::filesystem::path& path, const std::string& what, std::uintmax_t max_bytes,
                             const source_location& named_at)
{
    const std::string name = printable(utf8_text(path));
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

} // namespace detail

} // namespace rt
