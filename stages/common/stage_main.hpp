// stage_main.hpp - what every stage program shares: argument reading and the
// rule that any failure is one line on stderr and a non-zero exit.
#pragma once

#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include <rt/atomic_file.hpp>
#include <rt/error.hpp>
#include <rt/os_error.hpp>

namespace stage {

/// The command line after the program name, read left to right.
class arguments {
public:
    arguments(int argc, char** argv) : list_(argv + 1, argv + argc) {}

    bool done() const { return next_ >= list_.size(); }
    const std::string& peek() const { return list_[next_]; }
    std::string take() { return list_[next_++]; }

    /// The value after an option such as -o; an error if there is none.
    std::string value_of(const std::string& option)
    {
        if (done())
            throw rt::error("option " + option + ": expected a value after it, found the end of the command line; see --help");
        return take();
    }

private:
    std::vector<std::string> list_;
    std::size_t next_ = 0;
};

/// The command line every stage program reads: one scene file and options.
/// `option(arg)` consumes an option the program knows (reading its values
/// from `args`) and returns true, false for one it does not know. --help and
/// -h print `usage` and give nullopt (the program exits 0); an unknown option,
/// a second file or no file at all is an rt::error naming what was expected,
/// with `known` listing the options. Returns the scene file's path.
/// `input` names the file in messages, with its article: "a scene file", "an OBJ or scene file".
template <class Option>
std::optional<std::string> read_command_line(arguments& args, const std::string& usage, const std::string& known,
                                             Option&& option, const std::string& input = "a scene file")
{
    std::string scene_path;
    while (!args.done()) {
        const std::string arg = args.take();
        if (arg == "--help" || arg == "-h") {
            std::cout << usage;
            return std::nullopt;
        }
        if (option(arg))
            continue;
        if (!arg.empty() && arg[0] == '-')
            throw rt::error("expected an option (" + known + ", --help), found '" + arg + "'; see --help");
        if (!scene_path.empty())
            throw rt::error("expected one " + input.substr(input.find(' ') + 1) + ", found also '" + arg +
                            "'; see --help");
        scene_path = arg;
    }
    if (scene_path.empty())
        throw rt::error("expected " + input + ", found none; see --help");
    return scene_path;
}

/// --pixel I J or --pixel-json I J: the pixel whose story a program tells
/// (pixel_story.hpp) instead of writing its image.
struct pixel_request {
    bool wanted = false;
    bool json = false;
    int column = 0, row = 0;  ///< from the left, from the top (the stored image's convention)
};

/// The help lines every program from stage 03 on prints for --pixel.
inline const char* pixel_help =
    "  --pixel I J      tell the story of one pixel instead of writing images: its camera\n"
    "                   ray, every hit, light and shadow ray, and its colour; I is the\n"
    "                   column from the left, J the row from the top (as image viewers count)\n"
    "  --pixel-json I J the same as JSON (infinities are null)\n";

/// Reads "I J" after `option` (--pixel or --pixel-json): two whole numbers >= 0.
inline void read_pixel(arguments& args, const std::string& option, pixel_request& p)
{
    int values[2] = {0, 0};
    for (int& value : values) {
        const std::string text = args.value_of(option);
        const bool digits = !text.empty() && text.size() <= 9 && text.find_first_not_of("0123456789") == std::string::npos;
        if (!digits)
            throw rt::error(option + ": expected two whole numbers I J (column from the left, row from the top), found '" +
                            text + "'; see --help");
        value = std::stoi(text);
    }
    p.wanted = true;
    p.json = option == "--pixel-json";
    p.column = values[0];
    p.row = values[1];
}

/// `message` as one line: every control character (a line break in a path or
/// an argument) becomes '?', so a message is never split over two lines.
inline std::string one_line(const std::string& message)
{
    std::string line = message;
    for (char& c : line)
        if (static_cast<unsigned char>(c) < 32 || c == 127)
            c = '?';
    return line;
}

/// Runs `body`, turning every exception into one line "program: message" on
/// stderr and exit code 1, a usage error included (3 for an unfinished exercise).
template <class Body>
int run(const char* program, Body&& body)
{
    try {
        return body();
    } catch (const rt::exercise_not_done& e) {
        std::cerr << program << ": not done yet: " << one_line(e.what()) << '\n';
        return 3;
    } catch (const rt::error& e) {
        std::cerr << program << ": " << one_line(e.what()) << '\n';
        return 1;
    } catch (const std::bad_alloc&) {
        const std::uint64_t limit = rt::memory_limit();
        std::cerr << program << ": expected enough memory for the work, found an allocation refused ("
                  << (limit > 0 ? "the memory limit, ulimit -v, is " + rt::mebibytes(limit)
                                : std::string("the machine's memory is used up"))
                  << "); make the image or the scene smaller\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << program << ": error: " << one_line(e.what()) << '\n';
        return 1;
    }
}

/// The check every program makes before any work that reads `input` (a scene
/// or an OBJ file) and writes `outputs`: the input can be read (or the reason,
/// from errno), and no output is the input itself (device and inode). Call
/// rt::check_not_input(outputs, rt::files_read(input, scene)) again after
/// loading, for the OBJ and MTL files the input named.
inline void check_input_and_outputs(const std::string& input, const std::string& what,
                                    const std::vector<std::filesystem::path>& outputs)
{
    rt::check_readable(input, what);
    rt::check_not_input(outputs, {input});
}

} // namespace stage
