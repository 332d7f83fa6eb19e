// temporary_file.hpp - a temporary file beside its target that is removed
// whatever happens: on an exception, and when the program is interrupted
// (SIGINT, SIGTERM or SIGHUP on POSIX; Ctrl+C, Ctrl+Break or the console
// closed on Windows).
//
// Usage (atomic_file.hpp is its one user):
//     rt::detail::registered_temporary guard(rt::detail::temporary_sibling("out.png"));
//     rt::detail::new_file file;
//     if (file.create(guard.path()) == 0)  // exclusive: never someone else's file
//         guard.created();                  // from now on removed unless released
//     ... write, sync, close, rename over the target, then guard.release() ...
//
// The registry of the files being written and the cleanup that reads it on an
// interrupt are in platform.hpp: a signal handler on POSIX, which removes
// every registered temporary file, then lets the signal kill the process as it
// would have (POSIX 2017, sec. 2.4.3, lists what a handler may call); a
// console handler on Windows (rt::set_interrupt_cleanup(false) installs
// neither). A write over the file size limit fails with EFBIG and is reported
// instead of killing the program: platform.hpp's new_file::write blocks SIGXFSZ
// in the writing thread while it writes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include "../core/error.hpp"
#include "os_error.hpp"
#include "path_text.hpp"
#include "platform.hpp"

namespace rt {
namespace detail {

/// A slot of the registry holding `path` while it exists; the destructor
/// removes the file unless release() was called (after its rename).
class registered_temporary {
public:
    explicit registered_temporary(const std::filesystem::path& path) : path_(path)
    {
        const std::filesystem::path::string_type& text = path.native();
        if (text.size() >= temporary_registry::path_capacity)
            throw error(source_location{utf8_text(path)},
                        "expected a path of at most " + std::to_string(temporary_registry::path_capacity - 1) + " " +
                            length_unit + ", found " + std::to_string(text.size()) + "; shorten it");
        for (int k = 0; k < temporary_registry::slots; ++k) {
            int expected = temporary_registry::free_slot;
            if (temporary_files.state[k].compare_exchange_strong(expected, temporary_registry::claimed)) {
                std::memcpy(temporary_files.paths[k], text.c_str(), (text.size() + 1) * sizeof(text[0]));
                temporary_files.state[k].store(temporary_registry::registered);
                slot_ = k;
                return;
            }
        }
        throw error(source_location{utf8_text(path)}, "expected at most " + std::to_string(temporary_registry::slots) +
                                                          " files written at once, found more; write fewer at a time");
    }
    registered_temporary(const registered_temporary&) = delete;
    registered_temporary& operator=(const registered_temporary&) = delete;
    ~registered_temporary()
    {
        if (created_ && !released_)
            remove_file(path_);
        forget();
    }

    const std::filesystem::path& path() const { return path_; }

    /// The file now exists and is ours (created exclusively): remove it at the end.
    void created() { created_ = true; }

    /// The file was renamed: it is no longer a temporary file.
    void release()
    {
        released_ = true;
        forget();
    }

private:
    void forget()
    {
        if (slot_ < 0)
            return;
        int expected = temporary_registry::registered;
        // a failed exchange means the interrupt cleanup is removing it: the process is ending
        temporary_files.state[slot_].compare_exchange_strong(expected, temporary_registry::free_slot);
        slot_ = -1;
    }

    std::filesystem::path path_;
    int slot_ = -1;
    bool created_ = false;
    bool released_ = false;
};

/// A temporary name beside `target`: "<name>.tmp-<16 hex digits>", random
/// (std::random_device), so two threads or processes never pick the same one.
/// A name too long for the folder with the suffix is cut to fit. The name is
/// handled in the system's own characters (UTF-16 on Windows, where the limit
/// counts them), so any name stays as it was but for the cut.
inline std::filesystem::path temporary_sibling(const std::filesystem::path& target)
{
    static constexpr std::size_t suffix_length = 21; // ".tmp-" and 16 hex digits
    std::random_device entropy;
    const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : ".";
    std::filesystem::path::string_type name = target.filename().native();
    const std::size_t longest = name_max(folder);
    if (name.size() + suffix_length > longest) {
        name.resize(longest > suffix_length ? longest - suffix_length : 1);
        // never half of a UTF-16 surrogate pair (a char on POSIX is never in 0xD800-0xDBFF)
        if (name.size() > 1 && std::uint32_t(name.back()) - 0xD800u < 0x400u)
            name.pop_back();
    }
    const std::uint64_t high = entropy(), low = entropy();
    const std::uint64_t number = (high << 32) ^ low;
    static const char digits[] = "0123456789abcdef";
    std::string suffix = ".tmp-";
    for (int shift = 60; shift >= 0; shift -= 4)
        suffix += digits[(number >> shift) & 0xfu];
    name.append(suffix.begin(), suffix.end()); // ASCII: the same characters in any encoding
    return target.has_parent_path() ? target.parent_path() / name : std::filesystem::path(name);
}

} // namespace detail
} // namespace rt
