// atomic_file.hpp - write a file completely or not at all.
//
// Every output rt writes goes to a temporary file in the same folder first and
// is renamed over the target only when it is complete. A rename within one
// folder is atomic on POSIX file systems, so a reader sees either the old file
// or the new one, and a failure (a full disk, a crash, an exception while
// encoding) leaves the previous file untouched.
#pragma once

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <system_error>
#include <vector>

#include "error.hpp"

namespace rt {

namespace detail {

/// A temporary name beside `target` that no file has yet: a random number from
/// std::random_device, so two threads or processes never pick the same one.
inline std::filesystem::path temporary_sibling(const std::filesystem::path& target)
{
    std::random_device entropy;
    for (;;) {
        std::filesystem::path candidate = target;
        candidate += ".tmp-" + std::to_string(entropy()) + std::to_string(entropy());
        std::error_code ec;
        if (!std::filesystem::exists(candidate, ec))
            return candidate;
    }
}

} // namespace detail

/// Throws rt::error unless a file can be created at `target` (its folder exists,
/// is a folder and is writable, and `target` is not a folder). Call it before a
/// long render, so a bad output path fails at once instead of at the end.
inline void check_writable(const std::filesystem::path& target)
{
    std::error_code ec;
    if (std::filesystem::is_directory(target, ec))
        throw error(source_location{target.string()},
                    "expected an output file, found a folder; give a file name such as out.png");
    const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : ".";
    if (!std::filesystem::is_directory(folder, ec))
        throw error(source_location{target.string()},
                    "expected an existing output folder, found none at '" + folder.string() +
                        "'; create it first");
    const std::filesystem::path probe = detail::temporary_sibling(target);
    {
        std::ofstream out(probe, std::ios::binary);
        if (!out)
            throw error(source_location{target.string()},
                        "expected a writable output folder, found '" + folder.string() +
                            "' not writable; choose another output path");
    }
    std::filesystem::remove(probe, ec);
}

/// Throws rt::error when `target` is the same file as one of `inputs`, however
/// either path is spelled (std::filesystem::equivalent: same device and inode),
/// so that writing an output can never destroy what a program read. Call it
/// with check_writable, before any work.
inline void check_not_input(const std::filesystem::path& target, const std::vector<std::filesystem::path>& inputs)
{
    std::error_code ec;
    if (!std::filesystem::exists(target, ec))
        return; // a new file cannot be one of the inputs, which exist
    for (const std::filesystem::path& input : inputs)
        if (std::filesystem::equivalent(target, input, ec))
            throw error(source_location{target.string()},
                        "expected an output path different from the input '" + shown_path(input.string()) +
                            "', found the same file; writing it would destroy the input, so choose another -o");
}

/// Writes `target` atomically: `write(std::ostream&)` fills a temporary file,
/// which replaces `target` only if everything succeeded. Throws rt::error.
template <class Writer>
void write_atomically(const std::filesystem::path& target, Writer&& write)
{
    check_writable(target);
    const std::filesystem::path temporary = detail::temporary_sibling(target);
    std::error_code ec;
    try {
        {
            std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
            if (!out)
                throw error(source_location{target.string()}, "cannot create a temporary file beside it");
            write(static_cast<std::ostream&>(out));
            out.flush();
            if (!out)
                throw error(source_location{target.string()},
                            "writing failed (disk full?); the previous file, if any, is unchanged");
        }
        std::filesystem::rename(temporary, target, ec);
        if (ec)
            throw error(source_location{target.string()}, "cannot replace the file: " + ec.message());
    } catch (...) {
        std::filesystem::remove(temporary, ec);
        throw;
    }
}

} // namespace rt
