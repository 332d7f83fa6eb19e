// command_line.hpp - the one option parser of rt's programs: the stage
// programs, stage 08, the viewer and the benchmarks read their command lines
// with it, so every option error is the same one line,
//     option --spp: expected an integer from 1 to 65536, found 'abc'; see --help
// and a program exits 1 with it (stage_main.hpp's run()).
//
// Usage:
//     stage::arguments args(argc, argv);
//     std::string output = "out.png";
//     int depth = 5;
//     const std::optional<std::string> scene = stage::read_command_line(
//         args, usage, "-o, --max-depth", [&](const std::string& arg) {
//             if (arg == "-o")
//                 output = args.value_of(arg);
//             else if (arg == "--max-depth")
//                 depth = int(stage::parse_integer(arg, args.value_of(arg), 0, 64));
//             else
//                 return false;                  // not one of ours: an error naming the known ones
//             return true;
//         });
//     if (!scene) return 0;                      // --help printed the usage
//
// Options come before, after or between the operands; "--help" and "-h" print
// the usage. Nothing here knows rt's scenes: only rt::error.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <rt/core/config.hpp>
#include <rt/core/decimal_text.hpp>
#include <rt/core/error.hpp>
#include <rt/system/path_text.hpp>

namespace stage {

/// The command line after the program name, read left to right.
class arguments {
public:
    arguments(int argc, char** argv) : list_(argv + 1, argv + argc)
    {
        for (int k = 0; k < argc; ++k)
            command_ += (k ? " " : "") + std::string(argv[k]);
    }

    bool done() const { return next_ >= list_.size(); }
    const std::string& peek() const { return list_[next_]; }
    std::string take() { return list_[next_++]; }

    /// The value after an option such as -o; an error if there is none.
    std::string value_of(const std::string& option)
    {
        if (done())
            throw rt::error("option " + option +
                            ": expected a value after it, found the end of the command line; see --help");
        return take();
    }

    /// The whole command line as typed, program name included (benchmarks record it).
    const std::string& command() const { return command_; }

private:
    std::vector<std::string> list_;
    std::size_t next_ = 0;
    std::string command_;
};

/// The file that command-line text names. The text is UTF-8 (on Linux and
/// macOS as typed; on Windows the programs' manifest, stages/common/windows,
/// makes it so), while a std::filesystem::path made from a std::string reads
/// the native narrow encoding, which MinGW's library takes byte by byte: so
/// every path from the command line is made here, and "scène.scene" opens
/// the same file on every system.
inline std::filesystem::path file_argument(const std::string& text)
{
    return rt::detail::utf8_path(text);
}

inline std::string quoted(const std::string& text)
{
    return "'" + text + "'";
}

inline std::string number_text(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

/// The error of an option whose value is not what it takes.
inline rt::error option_error(const std::string& option, const std::string& expected, const std::string& found)
{
    return rt::error("option " + option + ": expected " + expected + ", found " + quoted(found) + "; see --help");
}

/// A whole number in [lo, hi].
inline long long parse_integer(const std::string& option, const std::string& text, long long lo, long long hi)
{
    std::size_t used = 0;
    long long value = 0;
    try {
        value = std::stoll(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || value < lo || value > hi)
        throw option_error(option, "an integer from " + std::to_string(lo) + " to " + std::to_string(hi), text);
    return value;
}

/// A whole number from 0 to 2^64 - 1 (a seed).
inline std::uint64_t parse_seed(const std::string& option, const std::string& text)
{
    std::size_t used = 0;
    unsigned long long value = 0;
    try {
        if (!text.empty() && text[0] != '-')
            value = std::stoull(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size())
        throw option_error(option, "an integer from 0 to 18446744073709551615", text);
    return value;
}

/// A finite number in [lo, hi] (lo excluded when `open_below`), written as
/// in a scene file and read as the scene loader reads it (rt/core/decimal_text.hpp:
/// the same in every locale, no blanks, no hexadecimal; the rt::real nearest
/// the text, so that rt::exact_number_text's text comes back exactly).
inline double parse_number(const std::string& option, const std::string& text, double lo, double hi,
                           bool open_below = false)
{
    double value = 0;
    const bool read = rt::detail::read_decimal<rt::real>(text.data(), text.data() + text.size(), value) ==
                      rt::detail::decimal_reading::number;
    const bool low_ok = open_below ? value > lo : value >= lo;
    if (!read || !low_ok || value > hi)
        throw option_error(option, std::string("a number in ") + (open_below ? "(" : "[") + number_text(lo) + ", " +
                                       number_text(hi) + "]",
                           text);
    return value;
}

/// WxH such as 800x600, each side 1 to 16384, into width and height.
inline void parse_size(const std::string& option, const std::string& text, int& width, int& height)
{
    const std::size_t x = text.find('x');
    if (x == std::string::npos)
        throw option_error(option, "WxH such as 800x600", text);
    width = int(parse_integer(option + " (width)", text.substr(0, x), 1, 16384));
    height = int(parse_integer(option + " (height)", text.substr(x + 1), 1, 16384));
}

/// One of `choices`, spelled exactly.
inline std::string parse_choice(const std::string& option, const std::string& text,
                                std::initializer_list<const char*> choices)
{
    std::string listed;
    std::size_t k = 0;
    for (const char* choice : choices) {
        if (text == choice)
            return text;
        listed += (k == 0 ? "" : k + 1 == choices.size() ? " or " : ", ") + std::string(choice);
        ++k;
    }
    throw option_error(option, listed, text);
}

/// A name an enum's table knows (enum_names.hpp: `from_name`), `choices` listing them.
template <class Kind>
Kind parse_name(const std::string& option, const std::string& text, std::optional<Kind> (*from_name)(const std::string&),
                const std::string& choices)
{
    const std::optional<Kind> kind = from_name(text);
    if (!kind)
        throw option_error(option, "one of " + choices, text);
    return *kind;
}

/// Reads every word of the command line: --help and -h print `usage` and give
/// nullopt (the program exits 0); `option(arg)` consumes an option the program
/// knows (reading its values from `args`) and returns true, false for one it
/// does not know, which is an error listing `known` ("-o, --spp"; empty for a
/// program without options); every other word is an operand, returned in order.
template <class Option>
std::optional<std::vector<std::string>> read_operands(arguments& args, const std::string& usage,
                                                      const std::string& known, Option&& option)
{
    std::vector<std::string> operands;
    while (!args.done()) {
        const std::string arg = args.take();
        if (arg == "--help" || arg == "-h") {
            std::cout << usage;
            return std::nullopt;
        }
        if (option(arg))
            continue;
        if (!arg.empty() && arg[0] == '-')
            throw rt::error("expected an option (" + (known.empty() ? "" : known + ", ") + "--help), found " +
                            quoted(arg) + "; see --help");
        operands.push_back(arg);
    }
    return operands;
}

/// read_operands for a program of one input file: a second file or none at
/// all is an error. `input` names the file with its article ("a scene file",
/// "an OBJ or scene file"); `optional_input` lets it be absent (an empty path).
template <class Option>
std::optional<std::string> read_command_line(arguments& args, const std::string& usage, const std::string& known,
                                             Option&& option, const std::string& input = "a scene file",
                                             bool optional_input = false)
{
    const std::optional<std::vector<std::string>> operands = read_operands(args, usage, known, option);
    if (!operands)
        return std::nullopt;
    if (operands->size() > 1)
        throw rt::error("expected one " + input.substr(input.find(' ') + 1) + ", found also " +
                        quoted((*operands)[1]) + "; see --help");
    if (operands->empty() && !optional_input)
        throw rt::error("expected " + input + ", found none; see --help");
    return operands->empty() ? std::string() : operands->front();
}

} // namespace stage
