// stage_main.hpp - what every stage program shares: the command line
// (command_line.hpp), --pixel, and the rule that any failure is one line on
// stderr and a non-zero exit.
#pragma once

#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include <rt/core/error.hpp>
#include <rt/scene/scene.hpp>
#include <rt/system/atomic_file.hpp>
#include <rt/system/os_error.hpp>
#include <rt/system/platform.hpp>

#include "command_line.hpp"

namespace stage {

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
    "                   ray, every hit, light and shadow ray, and its color; I is the\n"
    "                   column from the left, J the row from the top (as image viewers count)\n"
    "  --pixel-json I J the same as JSON (infinities are null)\n";

/// Reads "I J" after `option` (--pixel or --pixel-json): two whole numbers >= 0.
inline void read_pixel(arguments& args, const std::string& option, pixel_request& p)
{
    const char* const expected = "two whole numbers I J (column from the left, row from the top)";
    int values[2] = {0, 0};
    for (int& value : values) {
        if (args.done())
            throw rt::error("option " + option + ": expected " + expected +
                            ", found the end of the command line; see --help");
        const std::string text = args.take();
        const bool digits = !text.empty() && text.size() <= 9 && text.find_first_not_of("0123456789") == std::string::npos;
        if (!digits)
            throw option_error(option, expected, text);
        value = std::stoi(text);
    }
    p.wanted = true;
    p.json = option == "--pixel-json";
    p.column = values[0];
    p.row = values[1];
}

/// -o OUTPUT, --pixel I J and --pixel-json I J, which every program from stage
/// 03 on reads: true when `arg` was one of them (and its values are read).
inline bool read_image_option(arguments& args, const std::string& arg, std::string& output, pixel_request& pixel)
{
    if (arg == "-o")
        output = args.value_of(arg);
    else if (arg == "--pixel" || arg == "--pixel-json")
        read_pixel(args, arg, pixel);
    else
        return false;
    return true;
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
    [[maybe_unused]] rt::detail::utf8_console console; // messages name files in UTF-8
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
                  << (limit > 0 ? "the memory limit, ulimit -v, is " + rt::detail::mebibytes(limit)
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
    rt::check_readable(file_argument(input), what);
    rt::check_not_input(outputs, {file_argument(input)});
}

/// check_input_and_outputs, after checking that each output can be written:
/// a program that writes several files fails before the work, not after it.
inline void check_writable_outputs(const std::string& input, const std::string& what,
                                   const std::vector<std::filesystem::path>& outputs)
{
    for (const std::filesystem::path& output : outputs)
        rt::check_writable(output);
    check_input_and_outputs(input, what, outputs);
}

/// After the load: no output is a file the scene read (its OBJ and MTL files),
/// and `bytes` of images fit the memory limit (`what` names them in the error).
inline void check_after_load(const std::string& input, const rt::scene& s,
                             const std::vector<std::filesystem::path>& outputs, std::uint64_t bytes,
                             const std::string& what)
{
    rt::check_not_input(outputs, rt::files_read(file_argument(input), s));
    rt::check_memory_for(bytes, what);
}

} // namespace stage
