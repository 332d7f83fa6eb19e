// platform.hpp - every call rt makes to the operating system, in one place:
// creating, syncing, renaming and removing files, asking what a path is,
// removing temporary files when the program is interrupted, the memory limit,
// whether stderr is a terminal, a console that shows UTF-8. (The BVH's huge
// pages are platform_pages.hpp's: the fast path never sees <windows.h> and its
// macros.)
//
// Usage (the library's own headers are its users):
//     rt::detail::new_file file;
//     int code = file.create(temporary);                  // never an existing file
//     if (code == 0) code = file.write(bytes, count);     // every byte, or why not
//     if (code == 0) code = file.sync();                  // on the disk before the rename
//     if (const int closed = file.close(); code == 0) code = closed;
//     if (code == 0) code = rt::detail::replace_file(temporary, target);
//     if (code != 0) ... rt::detail::reason_of(code) says why ...
//
// Three branches, each complete: POSIX (IEEE Std 1003.1-2017: Linux, macOS),
// Windows (_WIN32: the Win32 API as Microsoft Learn documents it, through its
// wide-character functions, so that a path is UTF-16 and any name can be
// written), and a fallback in standard C++ alone for any other system (no
// exclusive create, no cleanup on an interrupt, no durable write). A failure
// is an errno value on every branch (Windows' error codes are mapped by
// errno_of), so that one function, reason_of in os_error.hpp, words every
// message.
//
// Why one header: these are the only calls outside standard C++, so every
// other header (but platform_pages.hpp) is the same on every system and
// includes no system header of its own. The systems' macros still reach whoever includes this header:
// windows.h defines near and far as nothing (minwindef.h) and ERROR, OPAQUE,
// TRANSPARENT (wingdi.h), so no name in rt may be one of those.
#pragma once

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

#if defined(_WIN32)
// windows.h without the rarely used APIs and without its min and max macros
// (which break std::min and glm::min), unless the includer chose otherwise.
#if !defined(WIN32_LEAN_AND_MEAN)
#define WIN32_LEAN_AND_MEAN
#define RT_PLATFORM_DEFINED_LEAN
#endif
#if !defined(NOMINMAX)
#define NOMINMAX
#define RT_PLATFORM_DEFINED_NOMINMAX
#endif
#include <windows.h>
#include <io.h>    // _isatty
#include <psapi.h> // GetProcessMemoryInfo
#if defined(RT_PLATFORM_DEFINED_LEAN)
#undef WIN32_LEAN_AND_MEAN
#undef RT_PLATFORM_DEFINED_LEAN
#endif
#if defined(RT_PLATFORM_DEFINED_NOMINMAX)
#undef NOMINMAX
#undef RT_PLATFORM_DEFINED_NOMINMAX
#endif
#elif defined(__unix__) || (defined(__APPLE__) && defined(__MACH__))
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace rt {
namespace detail {

/// What a path is, following symbolic links (as stat does).
struct file_status {
    int error = 0;        ///< 0, or why the path could not be examined (an errno value)
    bool folder = false;  ///< a folder
    bool regular = false; ///< a regular file (not a folder, device, pipe or socket)
};

/// The unit of path lengths, as messages name it: a path is bytes on POSIX and
/// UTF-16 code units on Windows (what its limits count; Microsoft Learn,
/// "Maximum Path Length Limitation", calls them characters).
inline constexpr const char* length_unit = sizeof(std::filesystem::path::value_type) == 1 ? "bytes" : "characters";

/// The length of `name`, in length_unit.
inline std::size_t path_length(const std::filesystem::path& name)
{
    return name.native().size();
}

// --- the registry of temporary files being written ---------------------------
//
// This is global mutable state, the one kind DEVELOPERS.md allows: the
// cleanup on an interrupt receives nothing but the signal number (POSIX) or
// the console event (Windows), so the paths it must remove can only be found
// through an object of static storage duration. On POSIX the cleanup is a
// signal handler, which may only make async-signal-safe calls (POSIX 2017,
// sec. 2.4.3: unlink, raise, sigaction; lock-free atomics); on Windows it runs
// on a thread of its own while the program goes on (Microsoft Learn,
// HandlerRoutine). So the registry is a fixed array of slots that each change
// hands by compare-and-swap, and no allocation, lock or exception touches it
// while an interrupt may arrive. Paths are kept as the system's own characters
// (wchar_t on Windows), ready for unlink or DeleteFileW.

struct temporary_registry {
    static constexpr int slots = 64;                ///< files being written at once, in all threads
    static constexpr std::size_t path_capacity = 4200; ///< PATH_MAX (4096) and a margin
    enum : int { free_slot = 0, claimed = 1, registered = 2, removing = 3 };
    std::atomic<int> state[slots];
    std::atomic<int> cleanup_off; ///< 1: rt::set_interrupt_cleanup(false), no handler is installed
    std::filesystem::path::value_type paths[slots][path_capacity];
};
static_assert(std::atomic<int>::is_always_lock_free, "the interrupt cleanup needs lock-free atomics");

/// The registry (zero-initialised: every slot free before any code runs).
inline temporary_registry temporary_files;

/// Removes every registered temporary file with `remove` (a function of the
/// path's characters that the cleanup may call), each at most once.
template <class Remove>
void remove_registered_temporaries(Remove remove)
{
    for (int k = 0; k < temporary_registry::slots; ++k) {
        int expected = temporary_registry::registered;
        if (temporary_files.state[k].compare_exchange_strong(expected, temporary_registry::removing))
            remove(temporary_files.paths[k]);
    }
}

#if defined(_WIN32)

// --- Windows (Win32 API, Microsoft Learn) ---------------------------------------

/// The errno value closest to a Win32 error code (Microsoft Learn, "System
/// Error Codes"), so that reason_of words Windows' failures as POSIX ones.
inline int errno_of(DWORD code)
{
    switch (code) {
    case ERROR_FILE_NOT_FOUND:
    case ERROR_PATH_NOT_FOUND:
        return ENOENT;
    case ERROR_ACCESS_DENIED:
    case ERROR_SHARING_VIOLATION: // another program has the file open
        return EACCES;
    case ERROR_DISK_FULL:
    case ERROR_HANDLE_DISK_FULL:
        return ENOSPC;
    case ERROR_FILENAME_EXCED_RANGE:
        return ENAMETOOLONG;
    case ERROR_DIRECTORY:
        return ENOTDIR;
    case ERROR_WRITE_PROTECT:
        return EROFS;
    case ERROR_ALREADY_EXISTS:
    case ERROR_FILE_EXISTS:
        return EEXIST;
    default:
        return EIO;
    }
}

/// errno_of the calling thread's last error (GetLastError).
inline int last_error()
{
    return errno_of(::GetLastError());
}

/// A file created for writing that must not exist before; closed at the end.
class new_file {
public:
    new_file() = default;
    new_file(const new_file&) = delete;
    new_file& operator=(const new_file&) = delete;
    ~new_file() { close(); }

    /// Creates `path`; 0, or why not. CreateFileW with CREATE_NEW fails when
    /// the file exists (ERROR_FILE_EXISTS), so it is never someone else's.
    /// FILE_SHARE_DELETE lets the cleanup of an interrupt, on its own thread,
    /// delete it while it is open here (DeleteFileW then removes it at its
    /// last CloseHandle: Microsoft Learn, CreateFileW, dwShareMode; DeleteFileW).
    int create(const std::filesystem::path& path)
    {
        handle_ = ::CreateFileW(path.c_str(), GENERIC_WRITE, FILE_SHARE_DELETE, nullptr, CREATE_NEW,
                                FILE_ATTRIBUTE_NORMAL, nullptr);
        return handle_ == INVALID_HANDLE_VALUE ? last_error() : 0;
    }

    /// Writes every byte; 0, or why not. WriteFile takes a DWORD count, so
    /// larger buffers go in pieces of 1 GiB.
    int write(const char* data, std::size_t count)
    {
        while (count > 0) {
            const DWORD piece = count > (std::size_t(1) << 30) ? DWORD(1) << 30 : DWORD(count);
            DWORD written = 0;
            if (!::WriteFile(handle_, data, piece, &written, nullptr))
                return last_error();
            if (written == 0)
                return EIO; // a disk file either takes bytes or fails: never loop on nothing
            data += written;
            count -= written;
        }
        return 0;
    }

    /// Puts the bytes on the device before the rename (FlushFileBuffers), so a
    /// power cut after it can never leave the new name on a file without its data.
    int sync() { return ::FlushFileBuffers(handle_) ? 0 : last_error(); }

    /// Closes the file (once); 0, or why it failed.
    int close()
    {
        if (handle_ == INVALID_HANDLE_VALUE)
            return 0;
        const HANDLE handle = handle_;
        handle_ = INVALID_HANDLE_VALUE;
        return ::CloseHandle(handle) ? 0 : last_error();
    }

private:
    HANDLE handle_ = INVALID_HANDLE_VALUE;
};

/// Renames `from` over `to`; 0, or why not. MoveFileExW with
/// MOVEFILE_REPLACE_EXISTING replaces an existing file, and
/// MOVEFILE_WRITE_THROUGH returns only once the move is on the disk (Microsoft
/// Learn, MoveFileExW). Not ReplaceFileW: it fails when the target does not
/// exist yet, so a first write would need another path, and it carries the old
/// file's attributes and security over to the new one, which rt does not
/// promise on POSIX either. Microsoft Learn does not call either function
/// atomic; see docs/reliability.md for what a write promises there.
inline int replace_file(const std::filesystem::path& from, const std::filesystem::path& to)
{
    return ::MoveFileExW(from.c_str(), to.c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH) ? 0
                                                                                                        : last_error();
}

/// Removes the file `path` (DeleteFileW); 0, or why not.
inline int remove_file(const std::filesystem::path& path)
{
    return ::DeleteFileW(path.c_str()) ? 0 : last_error();
}

/// What `path` is, following symbolic links: CreateFileW opens a link's target
/// (Microsoft Learn, CreateFileW, "Symbolic link behavior"), with
/// FILE_READ_ATTRIBUTES alone (no data is read) and FILE_FLAG_BACKUP_SEMANTICS,
/// without which a folder cannot be opened. GetFileType tells a disk file or
/// folder from a device (CON, NUL) or a pipe.
inline file_status status_of(const std::filesystem::path& path)
{
    const HANDLE handle = ::CreateFileW(path.c_str(), FILE_READ_ATTRIBUTES,
                                        FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE, nullptr, OPEN_EXISTING,
                                        FILE_FLAG_BACKUP_SEMANTICS, nullptr);
    if (handle == INVALID_HANDLE_VALUE)
        return {last_error(), false, false};
    file_status status;
    if (::GetFileType(handle) == FILE_TYPE_DISK) {
        BY_HANDLE_FILE_INFORMATION information{};
        if (::GetFileInformationByHandle(handle, &information)) {
            status.folder = (information.dwFileAttributes & FILE_ATTRIBUTE_DIRECTORY) != 0;
            status.regular = !status.folder;
        } else {
            status.error = last_error();
        }
    }
    ::CloseHandle(handle);
    return status;
}

/// True when `path` itself is a symbolic link (or another reparse point, such
/// as a junction): GetFileAttributesW does not follow it (Microsoft Learn,
/// GetFileAttributesW; "File Attribute Constants", FILE_ATTRIBUTE_REPARSE_POINT).
inline bool is_symbolic_link(const std::filesystem::path& path)
{
    const DWORD attributes = ::GetFileAttributesW(path.c_str());
    return attributes != INVALID_FILE_ATTRIBUTES && (attributes & FILE_ATTRIBUTE_REPARSE_POINT) != 0;
}

/// True when something is at `path`, a symbolic link to nothing included.
inline bool entry_exists(const std::filesystem::path& path)
{
    return ::GetFileAttributesW(path.c_str()) != INVALID_FILE_ATTRIBUTES;
}

/// 0 when the file `path` can be opened for reading, or why not.
inline int open_for_reading(const std::filesystem::path& path)
{
    const HANDLE handle = ::CreateFileW(path.c_str(), GENERIC_READ, FILE_SHARE_READ | FILE_SHARE_WRITE | FILE_SHARE_DELETE,
                                        nullptr, OPEN_EXISTING, FILE_ATTRIBUTE_NORMAL, nullptr);
    if (handle == INVALID_HANDLE_VALUE)
        return last_error();
    ::CloseHandle(handle);
    return 0;
}

/// The longest file name a folder accepts, in length_unit: 255 on NTFS, FAT32
/// and exFAT (Microsoft Learn, "Maximum Path Length Limitation";
/// GetVolumeInformationW reports it as lpMaximumComponentLength).
inline std::size_t longest_name(const std::filesystem::path&)
{
    return 255;
}

/// The longest path: MAX_PATH, 260 characters, for a program without the
/// longPathAware manifest entry (Microsoft Learn, "Maximum Path Length Limitation").
inline std::size_t longest_path()
{
    return MAX_PATH;
}

/// The cleanup of a console event (Ctrl+C, Ctrl+Break, the console closed, a
/// logoff, a shutdown): removes the temporary files, then returns FALSE, so
/// the next handler runs, in the end the default one, which ends the process
/// (Microsoft Learn, SetConsoleCtrlHandler, HandlerRoutine). It runs on a
/// thread of its own while the program keeps writing: a file it deletes
/// while open is removed when its handle closes (see new_file::create), and a
/// rename that comes first leaves the complete file, never a partial one.
inline BOOL WINAPI remove_temporaries_on_console_event(DWORD)
{
    remove_registered_temporaries([](const wchar_t* path) { ::DeleteFileW(path); });
    return FALSE;
}

/// Adds the cleanup to the process's console handlers, once. Windows offers
/// no way to ask whether the program handles Ctrl+C itself: handlers run
/// last-added first, so the cleanup runs before the program's own, and a
/// program that keeps running after Ctrl+C sees its write fail with a message
/// instead. A process without a console never receives these events.
/// Windows has no SIGXFSZ: a write past a quota fails with its error.
inline void install_cleanup_handlers()
{
    if (temporary_files.cleanup_off.load())
        return;
    static const bool installed = ::SetConsoleCtrlHandler(remove_temporaries_on_console_event, TRUE) != 0;
    (void)installed;
}

/// The process's address-space limit in bytes, or 0 when there is none:
/// Windows has no per-process limit like RLIMIT_AS (a job object's limit is
/// not read), so 0.
inline std::uint64_t process_memory_limit()
{
    return 0;
}

/// The process's memory in use, in bytes: PagefileUsage of
/// GetProcessMemoryInfo, the commit charge, the private memory the process
/// has allocated (Microsoft Learn, PROCESS_MEMORY_COUNTERS). It is what an
/// allocation adds to, like the address space that RLIMIT_AS counts on POSIX;
/// PrivateUsage (PROCESS_MEMORY_COUNTERS_EX) is documented as the same value.
/// psapi.h names K32GetProcessMemoryInfo of kernel32 by PSAPI_VERSION 2, the
/// default from Windows 7 on. 0 where it cannot be read.
inline std::uint64_t process_memory_in_use()
{
    PROCESS_MEMORY_COUNTERS counters{};
    counters.cb = sizeof counters;
    if (!::GetProcessMemoryInfo(::GetCurrentProcess(), &counters, sizeof counters))
        return 0;
    return std::uint64_t(counters.PagefileUsage);
}

/// True when stderr is a terminal (Microsoft Learn, _isatty and _fileno).
inline bool terminal_on_stderr()
{
    return ::_isatty(::_fileno(stderr)) != 0;
}

/// While it lives, a console window shows the program's UTF-8 output (rt's
/// messages name files as UTF-8, path_text.hpp) as UTF-8 rather than in its
/// OEM code page, where "scène" reads "scÃ¨ne"; the console's code page is
/// given back when it ends (Microsoft Learn, SetConsoleOutputCP). Output to a
/// file or a pipe is bytes either way.
class utf8_console {
public:
    utf8_console() : previous_(::GetConsoleOutputCP())
    {
        if (previous_ != 0 && previous_ != CP_UTF8 && ::SetConsoleOutputCP(CP_UTF8))
            changed_ = true;
    }
    ~utf8_console()
    {
        if (changed_)
            ::SetConsoleOutputCP(previous_);
    }
    utf8_console(const utf8_console&) = delete;
    utf8_console& operator=(const utf8_console&) = delete;

private:
    UINT previous_;
    bool changed_ = false;
};


#elif defined(__unix__) || (defined(__APPLE__) && defined(__MACH__))

// --- POSIX (IEEE Std 1003.1-2017) -----------------------------------------------

/// A file created for writing that must not exist before; closed at the end.
class new_file {
public:
    new_file() = default;
    new_file(const new_file&) = delete;
    new_file& operator=(const new_file&) = delete;
    ~new_file() { close(); }

    /// Creates `path`; 0, or errno. O_EXCL: fails when the file exists (a
    /// symbolic link included), so it is never someone else's (POSIX 2017, open()).
    int create(const std::filesystem::path& path)
    {
        do
            fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        while (fd_ < 0 && errno == EINTR);
        return fd_ < 0 ? errno : 0;
    }

    /// Writes every byte; 0, or errno. write() may write fewer bytes than
    /// asked, or none when a signal interrupts it (EINTR): both go on.
    ///
    /// A write past the file size limit (`ulimit -f`) raises SIGXFSZ, whose
    /// default action ends the process with a partial file, and fails with
    /// EFBIG (POSIX 2017, write()). So this thread blocks SIGXFSZ while it
    /// writes, takes back the signal its own write raised, and restores its
    /// mask: the limit becomes an error with a message, and nothing changes
    /// for other threads or for programs started later (a signal mask is per
    /// thread, sec. 2.4.1; an ignored SIGXFSZ would be inherited across exec).
    int write(const char* data, std::size_t count)
    {
        sigset_t file_size, previous;
        sigemptyset(&file_size);
        sigaddset(&file_size, SIGXFSZ);
        ::pthread_sigmask(SIG_BLOCK, &file_size, &previous);
        int result = 0;
        while (count > 0) {
            const ssize_t written = ::write(fd_, data, count);
            if (written < 0) {
                if (errno == EINTR)
                    continue;
                result = errno;
                break;
            }
            data += written;
            count -= std::size_t(written);
        }
        sigset_t pending;
        if (!sigismember(&previous, SIGXFSZ) && ::sigpending(&pending) == 0 && sigismember(&pending, SIGXFSZ)) {
            int taken = 0;
            ::sigwait(&file_size, &taken); // pending, so it returns at once
        }
        ::pthread_sigmask(SIG_SETMASK, &previous, nullptr);
        return result;
    }

    /// Puts the bytes on the device before the rename (fsync(), POSIX 2017): a
    /// file system may otherwise commit the rename before the data, and a
    /// power cut then leaves the new name on an empty or partial file.
    int sync()
    {
        int result;
        do
            result = ::fsync(fd_);
        while (result != 0 && errno == EINTR);
        return result != 0 ? errno : 0;
    }

    /// Closes the file (once); 0, or errno (NFS reports a full disk at close).
    /// Never retried: after EINTR the descriptor's state is unspecified (POSIX
    /// 2017, close()), and Linux has closed it already.
    int close()
    {
        if (fd_ < 0)
            return 0;
        const int fd = fd_;
        fd_ = -1;
        return ::close(fd) != 0 ? errno : 0;
    }

private:
    int fd_ = -1;
};

/// Renames `from` over `to`; 0, or errno. Within one file system rename() is
/// atomic: `to` names the old file or the new one, never neither (POSIX 2017, rename()).
inline int replace_file(const std::filesystem::path& from, const std::filesystem::path& to)
{
    return ::rename(from.c_str(), to.c_str()) != 0 ? errno : 0;
}

/// Removes the file `path` (unlink()); 0, or errno.
inline int remove_file(const std::filesystem::path& path)
{
    return ::unlink(path.c_str()) != 0 ? errno : 0;
}

/// What `path` is, following symbolic links (stat()).
inline file_status status_of(const std::filesystem::path& path)
{
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0)
        return {errno, false, false};
    return {0, S_ISDIR(status.st_mode) != 0, S_ISREG(status.st_mode) != 0};
}

/// True when `path` itself is a symbolic link (lstat() does not follow it).
inline bool is_symbolic_link(const std::filesystem::path& path)
{
    struct stat status {};
    return ::lstat(path.c_str(), &status) == 0 && S_ISLNK(status.st_mode);
}

/// True when something is at `path`, a symbolic link to nothing included.
inline bool entry_exists(const std::filesystem::path& path)
{
    struct stat status {};
    return ::lstat(path.c_str(), &status) == 0;
}

/// 0 when the file `path` can be opened for reading, or errno.
inline int open_for_reading(const std::filesystem::path& path)
{
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return errno;
    ::close(fd);
    return 0;
}

/// The longest file name (one path component) the folder `folder` accepts,
/// in bytes: pathconf(_PC_NAME_MAX), or 255 (NAME_MAX of Linux file systems)
/// when unknown.
inline std::size_t longest_name(const std::filesystem::path& folder)
{
    const long limit = ::pathconf(folder.c_str(), _PC_NAME_MAX);
    return limit > 0 ? std::size_t(limit) : std::size_t(255);
}

/// The longest path, in bytes: PATH_MAX (<limits.h>), or 4096, Linux's, where
/// the system leaves it undefined (POSIX 2017 allows that).
inline std::size_t longest_path()
{
#if defined(PATH_MAX)
    return PATH_MAX;
#else
    return 4096;
#endif
}

/// The signal handler: removes every registered temporary file, then restores
/// the default action and raises the signal again, so the program ends as the
/// signal would have ended it (the shell sees "killed by SIGINT", status 130).
/// Only async-signal-safe calls (POSIX 2017, sec. 2.4.3): unlink, sigaction,
/// sigemptyset, raise.
inline void remove_temporaries_and_die(int signal_number)
{
    remove_registered_temporaries([](const char* path) { ::unlink(path); });
    struct sigaction default_action {};
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    ::sigaction(signal_number, &default_action, nullptr);
    ::raise(signal_number); // blocked until the handler returns, then the default action
}

/// Installs the handler for SIGINT, SIGTERM and SIGHUP where their action is
/// the default one, unless rt::set_interrupt_cleanup(false) was called. Called
/// before every write: a few system calls, and a signal whose action the
/// program has set meanwhile (to handle or ignore it) is left so. SIGXFSZ is
/// new_file::write's, in the writing thread alone.
inline void install_cleanup_handlers()
{
    if (temporary_files.cleanup_off.load())
        return;
    for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction current {};
        if (::sigaction(signal_number, nullptr, &current) != 0 || (current.sa_flags & SA_SIGINFO) ||
            current.sa_handler != SIG_DFL)
            continue; // ours already, or ignored or handled by the program: leave it so
        struct sigaction cleanup {};
        cleanup.sa_handler = remove_temporaries_and_die;
        sigemptyset(&cleanup.sa_mask);
        sigaddset(&cleanup.sa_mask, SIGINT); // one cleanup at a time
        sigaddset(&cleanup.sa_mask, SIGTERM);
        sigaddset(&cleanup.sa_mask, SIGHUP);
        ::sigaction(signal_number, &cleanup, nullptr);
    }
}

/// The process's address-space limit in bytes (getrlimit(RLIMIT_AS), what
/// `ulimit -v` sets), or 0 when there is none.
inline std::uint64_t process_memory_limit()
{
    struct rlimit limit {};
    if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY)
        return 0;
    return std::uint64_t(limit.rlim_cur);
}

/// The process's address space in use now, in bytes: on Linux the first
/// field of /proc/self/statm, in pages (proc(5)), what RLIMIT_AS counts.
/// Elsewhere 0: macOS's task_info reports a virtual size that includes the
/// shared system libraries' reserved region, gigabytes no limit counts.
inline std::uint64_t process_memory_in_use()
{
#if defined(__linux__)
    std::ifstream statm("/proc/self/statm");
    std::uint64_t pages = 0;
    if (!(statm >> pages))
        return 0;
    const long page = ::sysconf(_SC_PAGESIZE);
    return pages * std::uint64_t(page > 0 ? page : 4096);
#else
    return 0;
#endif
}

/// True when stderr is a terminal (isatty(), POSIX 2017).
inline bool terminal_on_stderr()
{
    return ::isatty(STDERR_FILENO) != 0;
}

/// A terminal here shows UTF-8 as its locale says: nothing to change.
class utf8_console {
public:
    utf8_console() = default;
    utf8_console(const utf8_console&) = delete;
    utf8_console& operator=(const utf8_console&) = delete;
};

#else

// --- any other system: standard C++ alone ----------------------------------------

/// The errno value of a std::filesystem error, or EIO when it has none.
inline int errno_of(const std::error_code& code)
{
    const std::error_condition condition = code.default_error_condition();
    return condition.category() == std::generic_category() ? condition.value() : EIO;
}

/// A file created for writing; standard C++ has no exclusive create, so an
/// existing file is refused first (not atomically), and a failure has no
/// reason beyond EIO (std::ofstream does not say why).
class new_file {
public:
    int create(const std::filesystem::path& path)
    {
        std::error_code ec;
        if (std::filesystem::exists(std::filesystem::symlink_status(path, ec)))
            return EEXIST;
        out_.open(path, std::ios::binary);
        return out_ ? 0 : EIO;
    }
    int write(const char* data, std::size_t count)
    {
        out_.write(data, std::streamsize(count));
        return out_ ? 0 : EIO;
    }
    /// Standard C++ can only hand the bytes to the system, not to the device.
    int sync() { return out_.flush() ? 0 : EIO; }
    int close()
    {
        if (!out_.is_open())
            return 0;
        out_.close();
        return out_ ? 0 : EIO;
    }

private:
    std::ofstream out_;
};

/// Renames `from` over `to` (std::filesystem::rename replaces an existing file); 0, or why not.
inline int replace_file(const std::filesystem::path& from, const std::filesystem::path& to)
{
    std::error_code ec;
    std::filesystem::rename(from, to, ec);
    return ec ? errno_of(ec) : 0;
}

inline int remove_file(const std::filesystem::path& path)
{
    std::error_code ec;
    return std::filesystem::remove(path, ec) ? 0 : ec ? errno_of(ec) : ENOENT;
}

inline file_status status_of(const std::filesystem::path& path)
{
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (status.type() == std::filesystem::file_type::not_found)
        return {ENOENT, false, false};
    if (ec)
        return {errno_of(ec), false, false};
    return {0, std::filesystem::is_directory(status), std::filesystem::is_regular_file(status)};
}

inline bool is_symbolic_link(const std::filesystem::path& path)
{
    std::error_code ec;
    return std::filesystem::is_symlink(std::filesystem::symlink_status(path, ec));
}

inline bool entry_exists(const std::filesystem::path& path)
{
    std::error_code ec;
    return std::filesystem::exists(std::filesystem::symlink_status(path, ec));
}

inline int open_for_reading(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return in ? 0 : EIO;
}

/// Unknown here: 255, the most common file systems' limit.
inline std::size_t longest_name(const std::filesystem::path&)
{
    return 255;
}

/// Unknown here: 4096, Linux's PATH_MAX.
inline std::size_t longest_path()
{
    return 4096;
}

/// No cleanup on an interrupt in standard C++ (std::signal's handler may not
/// remove a file); an interrupted write may leave its temporary file.
inline void install_cleanup_handlers() {}

inline std::uint64_t process_memory_limit()
{
    return 0;
}

inline std::uint64_t process_memory_in_use()
{
    return 0;
}

/// Standard C++ cannot tell: not a terminal (no progress bar).
inline bool terminal_on_stderr()
{
    return false;
}

/// Nothing is known of the console here: nothing to change.
class utf8_console {
public:
    utf8_console() = default;
    utf8_console(const utf8_console&) = delete;
    utf8_console& operator=(const utf8_console&) = delete;
};

#endif

} // namespace detail
} // namespace rt
