// error.hpp - the two exceptions rt throws.
//
// rt::error carries a message that is already one complete line, in the form
//     file:line:col: expected <what>, found <what>; <hint>
// so a program prints e.what() and exits non-zero. rt::exercise_not_done is
// what a student kit's unfinished exercise throws.
#pragma once

#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace rt {

/// Where in an input file something was found. line and column count from 1;
/// 0 means "not known" and is left out of the message.
struct source_location {
    std::string file;
    int line = 0;
    int column = 0;
};

namespace detail {

/// A file name as a message shows it: control characters become '?', and a
/// path longer than 160 bytes keeps its last 160 or fewer (the file name is at
/// the end; the cut falls between UTF-8 characters), so that a message stays one
/// readable line whatever a file names.
inline std::string shown_path(const std::string& path)
{
    const std::size_t keep = 160;
    std::size_t from = path.size() > keep ? path.size() - keep : 0;
    while (from > 0 && from < path.size() && (static_cast<unsigned char>(path[from]) & 0xC0) == 0x80)
        ++from; // start on a whole UTF-8 character, not inside one
    std::string shown = from > 0 ? "..." + path.substr(from) : path;
    for (char& c : shown)
        if (static_cast<unsigned char>(c) < 32 || c == 127)
            c = '?';
    return shown;
}

} // namespace detail

/// "file:line:col" (or "file:line", or "file"), the prefix of every message.
inline std::string to_string(const source_location& where)
{
    std::string text = where.file.empty() ? std::string("<input>") : detail::shown_path(where.file);
    if (where.line > 0) {
        text += ':' + std::to_string(where.line);
        if (where.column > 0)
            text += ':' + std::to_string(where.column);
    }
    return text;
}

namespace detail {

/// Text from an input (a name, a path) made safe to print in a one-line
/// message: bytes that are not printable ASCII become '?', and anything past
/// `limit` characters is cut with "...".
inline std::string printable(const std::string& text, std::size_t limit = 200)
{
    std::string shown;
    for (char c : text.substr(0, limit))
        shown += (c >= 32 && c < 127) ? c : '?';
    return text.size() > limit ? shown + "..." : shown;
}

} // namespace detail

/// A bad input or a failed operation: the message is one line, ready to print.
class error : public std::runtime_error {
public:
    explicit error(const std::string& message) : std::runtime_error(message) {}
    error(const source_location& where, const std::string& message)
        : std::runtime_error(to_string(where) + ": " + message), where_(where) {}

    const source_location& where() const { return where_; }

private:
    source_location where_;
};

/// The standard message: "file:line:col: expected X, found Y; hint".
inline error make_error(const source_location& where, const std::string& expected,
                        const std::string& found, const std::string& hint = {})
{
    std::string message = "expected " + expected + ", found " + found;
    if (!hint.empty())
        message += "; " + hint;
    return error(where, message);
}

/// Thrown by an exercise a student has not written yet (see docs/student-guide.md).
class exercise_not_done : public std::logic_error {
public:
    explicit exercise_not_done(const std::string& what) : std::logic_error(what) {}
};

namespace detail {

/// A number for a message: six significant digits, as printf's %g.
inline std::string short_number(double x)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", x);
    return text;
}

} // namespace detail

} // namespace rt
