// os_error.hpp - why a file could not be read or written, in words a user can
// act on: the reason comes from errno (POSIX, IEEE Std 1003.1-2017, <errno.h>;
// on Windows the system's error mapped to errno by platform.hpp), so that "a
// folder you cannot enter", "a symbolic link loop" and "no such file" are
// three different messages, not one.
#pragma once

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <system_error>

#include "../core/error.hpp"
#include "path_text.hpp"
#include "platform.hpp"

namespace rt {

namespace detail {

/// What errno `code` means for a file, as the end of a message ("permission denied").
inline std::string reason_of(int code)
{
    switch (code) {
    case EACCES:
    case EPERM:
        return "permission denied";
    case ENOENT:
        return "no such file or folder";
    case ELOOP:
        return "too many symbolic links (a symbolic link loop?)";
    case ENAMETOOLONG:
        return "a name in the path, or the whole path, is too long";
    case ENOTDIR:
        return "a part of the path is a file, not a folder";
    case EISDIR:
        return "it is a folder";
    case EFBIG:
        return "the file size limit is reached (see ulimit -f)";
    case ENOSPC:
        return "the disk is full";
#ifdef EDQUOT
    case EDQUOT:
        return "the disk quota is used up";
#endif
    case EROFS:
        return "the file system is read-only";
    case EIO:
        return "an input/output error of the device";
    default:
        return std::error_code(code, std::generic_category()).message();
    }
}

/// The longest file name (one path component) the folder `folder` accepts, in
/// bytes on POSIX (pathconf(_PC_NAME_MAX), or 255, NAME_MAX of Linux file
/// systems, when unknown) and UTF-16 characters on Windows (255).
inline std::size_t name_max(const std::filesystem::path& folder)
{
    return detail::longest_name(folder);
}

} // namespace detail

/// Throws rt::error with the reason unless `path` can be opened for reading.
/// `what` names the file as a message says it ("a scene file", "an OBJ file").
/// A folder, a device, a pipe or a socket pass: the loaders refuse those with
/// their own words. Call it first, before any work.
inline void check_readable(const std::filesystem::path& path, const std::string& what)
{
    const source_location at{detail::utf8_text(path)};
    const detail::file_status status = detail::status_of(path);
    switch (status.error) {
    case 0:
        break;
    case ENOENT:
        if (detail::is_symbolic_link(path))
            throw error(at, "expected " + what + ", found a symbolic link to nothing; check where it points");
        throw error(at, "expected " + what + ", found no such file; check the path");
    case EACCES:
        throw error(at, "expected " + what + ", found a folder on its path that cannot be entered "
                                             "(permission denied); check the folders' permissions");
    case ELOOP:
        throw error(at, "expected " + what + ", found a symbolic link loop; check the links on the path");
    case ENAMETOOLONG:
        throw error(at, "expected " + what + ", found a path too long for the system (a name over " +
                            std::to_string(detail::name_max(".")) + " " + detail::length_unit + ", or the path over " +
                            std::to_string(detail::longest_path()) + "); shorten it");
    case ENOTDIR:
        throw error(at, "expected " + what + ", found a path that goes through a file as if it were a folder; "
                                             "check the path");
    default:
        throw error(at, "expected " + what + ", found one that cannot be examined (" + detail::reason_of(status.error) + ")");
    }
    if (!status.regular)
        return; // a folder or a special file: the loaders say what they expected
    const int code = detail::open_for_reading(path);
    if (code != 0)
        throw error(at, "expected " + what + " that can be read, found " +
                            (code == EACCES || code == EPERM ? std::string("one without read permission for this user")
                                                             : "one that cannot be opened (" + detail::reason_of(code) + ")") +
                            "; check its permissions");
}

/// The process's address-space limit in bytes (getrlimit(RLIMIT_AS), what
/// `ulimit -v` sets), or 0 when there is none (always on Windows).
inline std::uint64_t memory_limit()
{
    return detail::process_memory_limit();
}

namespace detail {

/// The process's memory in use now, in bytes, or 0 where it cannot be read:
/// on Linux its address space (the first field of /proc/self/statm, proc(5)),
/// on Windows its commit charge (platform.hpp says why).
inline std::uint64_t memory_in_use()
{
    return detail::process_memory_in_use();
}

/// "1234 MiB" (rounded up).
inline std::string mebibytes(std::uint64_t bytes)
{
    return std::to_string((bytes + (std::uint64_t(1) << 20) - 1) >> 20) + " MiB";
}

} // namespace detail

/// Throws rt::error, before any work, when `bytes` more (what `what` will
/// allocate at least) cannot fit under the memory limit (ulimit -v) beside what
/// the process uses already. Without a limit it passes: an allocation that
/// fails later is still reported (stage::run catches std::bad_alloc).
inline void check_memory_for(std::uint64_t bytes, const std::string& what)
{
    const std::uint64_t limit = memory_limit();
    if (limit == 0)
        return;
    const std::uint64_t used = detail::memory_in_use();
    if (bytes > limit || used + bytes > limit)
        throw error("expected " + what + " to fit in memory, found it needs at least " + detail::mebibytes(bytes) +
                    " while the memory limit (ulimit -v) is " + detail::mebibytes(limit) + " and " + detail::mebibytes(used) +
                    " are in use; make the image smaller, or render it in pieces with --crop");
}

} // namespace rt
