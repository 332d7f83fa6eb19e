// scene_statement.hpp - the words of a scene file's line (stage 01).
//
// A scene file (docs/scene-format.md) is read a line at a time: tokenize splits
// a line into words and "quoted strings", and a statement reads them left to
// right, each reader naming what it expects so that a problem becomes one line
//     file:line:col: expected <what>, found <what>; <hint>
// The readers of the scene file (scene_loader.hpp) and of the camera
// statement (camera_statement.hpp, the stage-01 exercise) both use it:
//
//     rt::statement line = ...;                 // "camera perspective eye 0 1 5"
//     const std::string kind = line.word("a camera type");
//     line.options({"eye"}, [&](const std::string& option) { eye = line.vector("eye"); return true; });
//     line.end();                               // nothing may be left over
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <istream>
#include <limits>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "config.hpp"
#include "error.hpp"
#include "vec.hpp"

namespace rt {

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
                throw parse_error(where, "a non-negative " + what, detail::short_number(double(value)), "colours cannot be negative");
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

} // namespace detail

} // namespace rt
