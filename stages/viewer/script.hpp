// script.hpp - the viewer's scripted input (--script), for tests and demos
// (no SDL here: main.cpp turns commands into SDL events).
//
// Commands are separated by newlines or ';', words by blanks; '#' starts a comment:
//     orbit DX DY       drag with the left button by (DX, DY) pixels (y down)
//     pan DX DY         drag with the right button
//     zoom STEPS        turn the wheel (positive: closer)
//     key NAME          press a key (an SDL key name: "5", "]", "s", "Escape")
//     click X Y         a left click at window pixel (X, Y) that does not move (the inspector's pick)
//     wait [LEVELS]     until the view is finished, or LEVELS levels are (the preview is 1)
//     sleep MS          let MS milliseconds pass
//     screenshot FILE   the window's pixels, read back, to FILE (.png or .ppm)
//     title FILE        the window's title, to FILE
//     save FILE         what the save key writes (the last finished level) to FILE
//     args FILE         the stage08_output arguments of that image, one a line, without -o
//     story FILE        the inspected pixel's story as JSON (stage08_output --pixel-json's)
//     quit              close the window
#pragma once

#include <cctype>
#include <cstddef>
#include <string>
#include <vector>

#include <rt/core/decimal_text.hpp>
#include <rt/core/error.hpp>

namespace viewer {

struct script_command {
    std::string name;
    std::vector<std::string> arguments;
    rt::source_location where;  ///< of the command's name
    /// Argument k, a number (parse_script checked it)
    double number(std::size_t k) const
    {
        double value = 0;
        rt::detail::read_decimal<double>(arguments[k].data(), arguments[k].data() + arguments[k].size(), value);
        return value;
    }
};

namespace detail {

struct script_word {
    std::string text;
    int column = 0;
};

/// The arity and argument kinds of each command: 'n' a number, 'i' a whole
/// number, 'w' a word, '?' an optional whole number.
inline const char* script_signature(const std::string& name)
{
    if (name == "orbit" || name == "pan")
        return "nn";
    if (name == "zoom")
        return "n";
    if (name == "key" || name == "screenshot" || name == "title" || name == "save" || name == "args" ||
        name == "story")
        return "w";
    if (name == "click")
        return "ii";
    if (name == "wait")
        return "?";
    if (name == "sleep")
        return "i";
    if (name == "quit")
        return "";
    return nullptr;
}

inline bool is_number(const std::string& text, bool whole)
{
    if (!whole) {
        // as a scene file's numbers are read (rt/core/decimal_text.hpp): the same in
        // every locale, no blanks, no hexadecimal
        double value = 0;
        return rt::detail::read_decimal<double>(text.data(), text.data() + text.size(), value) ==
                   rt::detail::decimal_reading::number &&
               value > -1e6 && value < 1e6;
    }
    if (text.empty())
        return false;
    std::size_t used = 0;
    try {
        const long long value = std::stoll(text, &used);
        if (value < 0 || value > 1000000)
            return false;
    } catch (const std::exception&) {
        return false;
    }
    return used == text.size();
}

} // namespace detail

/// The commands of a script; `name` starts the messages ("--script:1:7: expected ...").
inline std::vector<script_command> parse_script(const std::string& text, const std::string& name = "--script")
{
    std::vector<script_command> commands;
    int line = 1;
    std::size_t i = 0;
    std::size_t line_start = 0;
    std::vector<detail::script_word> words;
    auto finish = [&] {
        if (words.empty())
            return;
        script_command command;
        command.name = words[0].text;
        command.where = rt::source_location{name, line, words[0].column};
        const char* signature = detail::script_signature(command.name);
        if (!signature)
            throw rt::make_error(command.where,
                                 "a command (orbit, pan, zoom, key, click, wait, sleep, screenshot, title, save, "
                                 "args, story, quit)",
                                 "'" + command.name + "'");
        const std::string kinds = signature;
        const std::size_t given = words.size() - 1;
        const std::size_t required = kinds == "?" ? 0 : kinds.size();
        if (given < required || given > kinds.size()) {
            const int column = given > kinds.size() ? words[kinds.size() + 1].column : words.back().column;
            const rt::source_location at{name, line, column};
            throw rt::make_error(at, std::to_string(kinds.size()) + (kinds == "?" ? " or 0" : "") + " argument" +
                                         (kinds.size() == 1 ? "" : "s") + " after '" + command.name + "'",
                                 std::to_string(given));
        }
        for (std::size_t k = 0; k < given; ++k) {
            const char kind = kinds[k];
            const std::string& word = words[k + 1].text;
            if (kind != 'w' && !detail::is_number(word, kind != 'n')) {
                const std::string expected =
                    kind == 'n' ? "a number between -1e6 and 1e6" : "a whole number from 0 to 1000000";
                throw rt::make_error({name, line, words[k + 1].column}, expected, "'" + word + "'");
            }
            command.arguments.push_back(word);
        }
        commands.push_back(command);
        words.clear();
    };
    while (i < text.size()) {
        const char c = text[i];
        if (c == '\n' || c == ';') {
            finish();
            if (c == '\n') {
                ++line;
                line_start = i + 1;
            }
            ++i;
        } else if (c == '#') {
            while (i < text.size() && text[i] != '\n')
                ++i;
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
        } else {
            const std::size_t start = i;
            while (i < text.size() && text[i] != '\n' && text[i] != ';' && text[i] != '#' &&
                   !std::isspace(static_cast<unsigned char>(text[i])))
                ++i;
            words.push_back({text.substr(start, i - start), int(start - line_start) + 1});
        }
    }
    finish();
    return commands;
}

} // namespace viewer
