// stage_main.hpp - what every stage program shares: argument reading and the
// rule that any failure is one line on stderr and a non-zero exit.
#pragma once

#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include <rt/error.hpp>

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

/// Runs `body`, turning every exception into one line "program: message" on
/// stderr and exit code 1, a usage error included (3 for an unfinished exercise).
template <class Body>
int run(const char* program, Body&& body)
{
    try {
        return body();
    } catch (const rt::exercise_not_done& e) {
        std::cerr << program << ": not done yet: " << e.what() << '\n';
        return 3;
    } catch (const rt::error& e) {
        std::cerr << program << ": " << e.what() << '\n';
        return 1;
    } catch (const std::exception& e) {
        std::cerr << program << ": error: " << e.what() << '\n';
        return 1;
    }
}

} // namespace stage
