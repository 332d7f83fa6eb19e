// stage_main.hpp - what every stage program shares: argument reading and the
// rule that any failure is one line on stderr and a non-zero exit.
#pragma once

#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
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
