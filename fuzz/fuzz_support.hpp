// fuzz_support.hpp - what the libFuzzer targets share.
//
// The rule every target checks: any input ends in success or an rt::error
// whose message is one short printable line. Any other exception escapes the
// target, and libFuzzer reports it as a crash (uncaught exception -> abort).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <rt/core/error.hpp>
#include <rt/input/text_file.hpp> // rt::detail::utf8_length

namespace fuzz {

/// The longest message rt may print. A message names at most two files (paths
/// are shortened by rt::to_string) and quotes at most a few short tokens; any
/// longer message is dumping file contents.
constexpr std::size_t max_message_length = 1024;

/// Aborts (libFuzzer then saves the input) when an error message breaks the
/// one-line promise of DEVELOPERS.md: one line of text (printable ASCII, or
/// UTF-8 from a file name), short.
inline void check_message(const rt::error& e)
{
    const std::string message = e.what();
    bool printable = true;
    for (std::size_t i = 0; printable && i < message.size();) {
        const unsigned char c = static_cast<unsigned char>(message[i]);
        const std::size_t length = c < 32 || c == 127 ? 0 : rt::detail::utf8_length(message, i);
        printable = length > 0;
        i += length;
    }
    if (message.empty() || !printable || message.size() > max_message_length) {
        std::fprintf(stderr, "fuzz: bad error message (%zu bytes, printable %d): %.2000s\n", message.size(),
                     int(printable), message.c_str());
        std::abort();
    }
}

/// A fresh, empty folder for this process's input files, removed at exit.
class scratch_folder {
public:
    scratch_folder()
    {
        std::string pattern = (std::filesystem::temp_directory_path() / "rt-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data())) {
            std::perror("fuzz: mkdtemp");
            std::abort();
        }
        path_ = pattern;
    }
    ~scratch_folder()
    {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    scratch_folder(const scratch_folder&) = delete;
    scratch_folder& operator=(const scratch_folder&) = delete;

    const std::filesystem::path& path() const { return path_; }

    /// Writes `name` in the folder with exactly `text` (truncating what was there).
    void write(const std::string& name, const std::string& text) const
    {
        std::ofstream out(path_ / name, std::ios::binary | std::ios::trunc);
        out.write(text.data(), std::streamsize(text.size()));
        if (!out) {
            std::perror("fuzz: writing an input file");
            std::abort();
        }
    }

private:
    std::filesystem::path path_;
};

} // namespace fuzz
