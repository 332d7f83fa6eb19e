// scene_statement.hpp - the words of a scene file's line (stage 01).
//
// A scene file (docs/scene-format.md) is read a line at a time: tokenize
// (text_line.hpp, the tokenizer every file shares) splits a line into words and
// "quoted strings", and a statement reads them left to right, each reader naming what it expects so that a problem becomes one line
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

#include "../core/config.hpp"
#include "../core/error.hpp"
#include "text_line.hpp"
#include "../core/vec.hpp"

namespace rt {

namespace detail {

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

} // namespace detail

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
        const std::size_t distance = detail::edit_distance(prefix, known[i].substr(0, compared));
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
        return make_error(here(), expected, done() ? "the end of the line" : found_text(peek()), hint);
    }

    std::string word(const std::string& what)
    {
        if (done())
            throw unexpected(what);
        return tokens_[next_++].text;
    }

    /// A finite number (NaN, inf and numbers beyond rt::real's range are
    /// errors), read as text_line::number reads one.
    real number(const std::string& what)
    {
        if (done())
            throw unexpected("a number for " + what);
        const std::string& text = peek();
        const double largest = double(std::numeric_limits<real>::max());
        double value = 0;
        const auto reading = detail::read_number(text.data(), text.data() + text.size(), largest, value);
        if (reading != detail::number_reading::fits) {
            const detail::number_complaint complaint = detail::complain(reading, what, largest);
            throw unexpected(complaint.expected, complaint.hint);
        }
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
            throw make_error(where, "a non-zero " + what, "0 0 0", "a direction needs a length");
        return v;
    }

    /// An RGB color with non-negative components.
    color rgb(const std::string& what)
    {
        color c;
        for (int channel = 0; channel < 3; ++channel) {
            const source_location where = here();
            const real value = number(what + " " + "rgb"[channel]);
            if (value < 0)
                throw make_error(where, "a non-negative " + what, detail::short_number(double(value)), "colors cannot be negative");
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

} // namespace rt
