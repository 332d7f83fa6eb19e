// text_line.hpp - one line of a text file, read word by word: the one tokenizer
// of scene, OBJ and MTL files.
//
// Every file rt reads is text read a line at a time, and every problem in it
// becomes one line "file:line:col: expected <what>, found <what>; <hint>". A
// text_line is a cursor over one line: word() takes the next word (blanks
// separate words; a '#' where a word would start begins a comment), number()
// the next number, and unexpected() names what was expected where the cursor
// stands. The readers build on it:
//   scene_statement.hpp  tokenize() splits a scene line into tokens (scene files
//                        also have "quoted strings" and end a word at '#')
//   obj_line.hpp         the OBJ and MTL checks (what tinyobjloader cannot read)
//
//     std::vector<rt::line_piece> pieces = {{0, 7, 1}};   // the line is line 7 of "a.obj"
//     rt::text_line line("a.obj", pieces, text.data(), text.data() + text.size());
//     const std::string keyword = line.word();             // "v"
//     const rt::real x = line.number("the vertex x");      // or "a.obj:7:3: expected a number ..."
//
// The lines themselves come from text_file.hpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "../core/config.hpp"
#include "../core/decimal_text.hpp"
#include "../core/error.hpp"
#include "text_file.hpp"

namespace rt {

/// One word of a line and the column (from 1) where it starts.
struct token {
    std::string text;
    int column = 0;
};

/// How a line's words are written. OBJ and MTL files (the default): a word is
/// whatever lies between blanks, as tinyobjloader reads it. Scene files
/// (docs/scene-format.md): also "quoted strings" (paths with spaces), and a
/// '#' ends a word as well as starting a comment.
struct line_syntax {
    bool quotes = false;
    bool hash_ends_word = false;
};

namespace detail {

/// Why a word is not a number rt can store, or `fits`.
enum class number_reading { fits, not_a_number, not_finite, too_large };

/// Reads [first, last) as one decimal number (decimal_text.hpp: a leading
/// '+' allowed, nothing else skipped, whatever the locale) into `value`: the
/// rt::real nearest the text (as a double), or beyond rt::real's range the
/// double nearest it. A magnitude beyond `largest` (or beyond double) is
/// too_large; one below the smallest double is 0, as it is at any precision.
inline number_reading read_number(const char* first, const char* last, double largest, double& value)
{
    switch (read_decimal<real>(first, last, value)) {
    case decimal_reading::number:
        value = rounded_to<real>(value);
        return std::fabs(value) > largest ? number_reading::too_large : number_reading::fits;
    case decimal_reading::not_finite:
        return number_reading::not_finite;
    case decimal_reading::too_large:
        return number_reading::too_large;
    case decimal_reading::not_a_number:
        break;
    }
    return number_reading::not_a_number;
}

/// What a reader says of a word that is not a number it can store: the
/// "expected" and the hint of its error (both readers say the same).
struct number_complaint {
    std::string expected, hint;
};

inline number_complaint complain(number_reading reading, const std::string& what, double largest)
{
    const std::string for_what = what.empty() ? std::string() : " for " + what;
    switch (reading) {
    case number_reading::not_finite:
        return {"a finite number" + for_what, "NaN and inf are not allowed"};
    case number_reading::too_large: {
        std::ostringstream text;
        text << "a number" << for_what << " within +-" << largest;
        return {text.str(), "use smaller units"};
    }
    default:
        return {"a number" + for_what, ""};
    }
}

} // namespace detail

/// A cursor over one line of text (see the top of this file). The line's text,
/// the file name and the pieces must outlive it.
class text_line {
public:
    text_line(const std::string& file, const std::vector<line_piece>& pieces, const char* first, const char* last,
              line_syntax syntax = {})
        : file_(file), pieces_(pieces), begin_(first), next_(first), end_(last), syntax_(syntax)
    {
        skip_blanks();
    }

    // the cursor keeps references: a temporary file name or piece list would dangle
    text_line(std::string&&, const std::vector<line_piece>&, const char*, const char*, line_syntax = {}) = delete;
    text_line(const std::string&, std::vector<line_piece>&&, const char*, const char*, line_syntax = {}) = delete;

    /// Nothing left but blanks or a comment.
    bool done() const { return next_ == end_ || *next_ == '#'; }
    /// Nothing left at all (a comment is still there to read).
    bool at_end() const { return next_ == end_; }
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

    /// The next word (with line_syntax::quotes, a "quoted string" without its quotes).
    std::string word()
    {
        if (syntax_.quotes && next_ != end_ && *next_ == '"') {
            const char* close = std::find(next_ + 1, end_, '"');
            if (close == end_)
                throw make_error(here(), "a closing '\"'", "the end of the line");
            std::string text(next_ + 1, close);
            next_ = close + 1;
            skip_blanks();
            return text;
        }
        const char* start = next_;
        next_ = word_end();
        std::string text(start, next_);
        skip_blanks();
        return text;
    }

    /// An error at the cursor: "expected <expected>, found <the next word>".
    error unexpected(const std::string& expected, const std::string& hint = {}) const
    {
        return make_error(here(), expected, done() ? "the end of the line" : "'" + detail::printable(peek_word(), 24) + "'", hint);
    }

    /// A finite number of magnitude at most `largest` (rt::real's largest by
    /// default), the rt::real nearest the text (read_number); `move_on`
    /// false: only looks at it.
    real number(const std::string& what, bool move_on = true,
                double largest = double(std::numeric_limits<real>::max()))
    {
        if (done())
            throw unexpected("a number for " + what);
        const char* stop = word_end();
        double value = 0;
        const auto reading = detail::read_number(next_, stop, largest, value);
        if (reading != detail::number_reading::fits) {
            const detail::number_complaint complaint = detail::complain(reading, what, largest);
            throw unexpected(complaint.expected, complaint.hint);
        }
        if (move_on) {
            next_ = stop;
            skip_blanks();
        }
        return real(value);
    }

protected:
    void skip_blanks()
    {
        while (next_ != end_ && (*next_ == ' ' || *next_ == '\t' || *next_ == '\r'))
            ++next_;
    }

    /// Where the word at the cursor ends.
    const char* word_end() const
    {
        const char* stop = next_;
        while (stop != end_ && *stop != ' ' && *stop != '\t' && *stop != '\r' && !(syntax_.hash_ends_word && *stop == '#'))
            ++stop;
        return stop;
    }

    /// The next word as a message shows it: at most 24 printable characters.
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
    line_syntax syntax_;
};

namespace detail {

/// Splits one scene line into tokens with text_line's scene syntax: words,
/// "quoted strings" and a '#' that starts a comment (which may hold anything
/// but is not read); every token must be text (check_text).
inline std::vector<token> tokenize(const std::string& text, const source_location& where)
{
    const std::vector<line_piece> pieces = {{0, where.line, 1}};
    text_line line(where.file, pieces, text.data(), text.data() + text.size(), line_syntax{true, true});
    std::vector<token> tokens;
    while (!line.done()) {
        const int column = line.here().column;
        const bool quoted = text[std::size_t(column - 1)] == '"';
        token t{line.word(), column};
        const std::size_t start = std::size_t(column - 1) + (quoted ? 1 : 0);
        check_text(text, start, start + t.text.size(), where);
        tokens.push_back(std::move(t));
    }
    return tokens;
}

} // namespace detail

} // namespace rt
