// temporary_file.hpp - a temporary file beside its target that is removed
// whatever happens: on an exception, and when the program is stopped by
// SIGINT, SIGTERM or SIGHUP.
//
// Usage (atomic_file.hpp is its one user):
//     rt::detail::registered_temporary guard(rt::detail::temporary_sibling("out.png"));
//     const int fd = rt::detail::create_new_file(guard.path());  // O_EXCL: never someone else's
//     if (fd >= 0) guard.created();                // from now on removed unless released
//     ... write, fsync, rename over the target, then guard.release() ...
//
// The signal handler removes every registered temporary file, then lets the
// signal kill the process as it would have (POSIX 2017, sec. 2.4.3, lists what
// a handler may call). SIGXFSZ is ignored so that a write over the file size
// limit fails with EFBIG and is reported instead of killing the program.
#pragma once

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include "error.hpp"
#include "os_error.hpp"

namespace rt {
namespace detail {

// --- the registry of temporary files being written ---------------------------
//
// This is global mutable state, the one kind DEVELOPERS.md allows: a signal
// handler receives nothing but the signal number, so the paths it must remove
// can only be found through an object of static storage duration. The handler
// may only make async-signal-safe calls (POSIX 2017, sec. 2.4.3: unlink, raise,
// sigaction; lock-free atomics), so the registry is a fixed array of slots and
// no allocation, lock or exception touches it while a signal may arrive.

struct temporary_registry {
    static constexpr int slots = 64;              ///< files being written at once, in all threads
    static constexpr std::size_t path_bytes = 4200; ///< PATH_MAX (4096) and a margin
    enum : int { free_slot = 0, claimed = 1, registered = 2, removing = 3 };
    std::atomic<int> state[slots];
    char paths[slots][path_bytes];
};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler needs lock-free atomics");

/// The registry (zero-initialised: every slot free before any code runs).
inline temporary_registry temporary_files;

/// The signal handler: removes every registered temporary file, then restores
/// the default action and raises the signal again, so the program ends as the
/// signal would have ended it (the shell sees "killed by SIGINT", status 130).
inline void remove_temporaries_and_die(int signal_number)
{
    for (int k = 0; k < temporary_registry::slots; ++k) {
        int expected = temporary_registry::registered;
        if (temporary_files.state[k].compare_exchange_strong(expected, temporary_registry::removing))
            ::unlink(temporary_files.paths[k]);
    }
    struct sigaction default_action {};
    default_action.sa_handler = SIG_DFL;
    sigemptyset(&default_action.sa_mask);
    ::sigaction(signal_number, &default_action, nullptr);
    ::raise(signal_number); // blocked until the handler returns, then the default action
}

/// Installs the handler for SIGINT, SIGTERM and SIGHUP where their action is
/// the default one, and ignores SIGXFSZ where it is the default (so a write past
/// the file size limit fails with EFBIG instead of killing the program with a
/// partial file). Called before every write: a few system calls, and a signal
/// whose action the program has set meanwhile (to handle or ignore it) is left so.
inline void install_cleanup_handlers()
{
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
    struct sigaction current {};
    if (::sigaction(SIGXFSZ, nullptr, &current) == 0 && !(current.sa_flags & SA_SIGINFO) &&
        current.sa_handler == SIG_DFL) {
        struct sigaction ignore {};
        ignore.sa_handler = SIG_IGN;
        sigemptyset(&ignore.sa_mask);
        ::sigaction(SIGXFSZ, &ignore, nullptr);
    }
}

/// A slot of the registry holding `path` while it exists; the destructor
/// removes the file unless release() was called (after its rename).
class registered_temporary {
public:
    explicit registered_temporary(const std::filesystem::path& path) : path_(path)
    {
        const std::string text = path.string();
        if (text.size() >= temporary_registry::path_bytes)
            throw error(source_location{text}, "expected a path of at most " +
                                                   std::to_string(temporary_registry::path_bytes - 1) +
                                                   " bytes, found " + std::to_string(text.size()) + "; shorten it");
        for (int k = 0; k < temporary_registry::slots; ++k) {
            int expected = temporary_registry::free_slot;
            if (temporary_files.state[k].compare_exchange_strong(expected, temporary_registry::claimed)) {
                std::memcpy(temporary_files.paths[k], text.c_str(), text.size() + 1);
                temporary_files.state[k].store(temporary_registry::registered);
                slot_ = k;
                return;
            }
        }
        throw error(source_location{text}, "expected at most " + std::to_string(temporary_registry::slots) +
                                               " files written at once, found more; write fewer at a time");
    }
    registered_temporary(const registered_temporary&) = delete;
    registered_temporary& operator=(const registered_temporary&) = delete;
    ~registered_temporary()
    {
        if (created_ && !released_)
            ::unlink(path_.c_str());
        forget();
    }

    const std::filesystem::path& path() const { return path_; }

    /// The file now exists and is ours (created with O_EXCL): remove it at the end.
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
        // a failed exchange means a signal handler is removing it: the process is ending
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
/// A name too long for the folder with the suffix is cut to fit.
inline std::filesystem::path temporary_sibling(const std::filesystem::path& target)
{
    static constexpr std::size_t suffix_bytes = 21; // ".tmp-" and 16 hex digits
    std::random_device entropy;
    const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : ".";
    std::string name = target.filename().string();
    const std::size_t longest = name_max(folder);
    if (name.size() + suffix_bytes > longest)
        name.resize(longest > suffix_bytes ? longest - suffix_bytes : 1);
    const std::uint64_t high = entropy(), low = entropy();
    const std::uint64_t number = (high << 32) ^ low;
    static const char digits[] = "0123456789abcdef";
    std::string suffix = ".tmp-";
    for (int shift = 60; shift >= 0; shift -= 4)
        suffix += digits[(number >> shift) & 0xfu];
    return target.has_parent_path() ? target.parent_path() / (name + suffix) : std::filesystem::path(name + suffix);
}

/// Creates `path` (it must not exist) for writing; -1 and errno on failure.
inline int create_new_file(const std::filesystem::path& path)
{
    int fd;
    do
        fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    while (fd < 0 && errno == EINTR);
    return fd;
}

} // namespace detail
} // namespace rt
