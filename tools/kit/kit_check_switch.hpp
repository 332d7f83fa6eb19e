// tools/kit/kit_check_switch.hpp - what tools/check_kit.py's switchable kit adds to rt.
//
// tools/make_kit.py (switchable_plan) appends everything after `#pragma once` to
// that kit's include/rt/core/error.hpp; never part of a student's kit or of rt.
// It is a real header so that the build compiles it with rt's warnings
// (tests/CMakeLists.txt, the per-header check; POSIX only: it reads /proc).
#pragma once

// check_kit's switchable kit: RT_KIT_STRIP=5 (or 5,7) makes the exercises of
// those stages throw their not-done message, as a kit that strips them would.
// RT_KIT_TRACE=<folder> records which stages' exercises each ctest test asks
// about (kit_check_trace), so that check_kit reruns, for stage N, only the
// tests that reach a stage-N exercise: the others run the same code whatever
// RT_KIT_STRIP says.
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <string>

#include <fcntl.h>
#include <unistd.h>

namespace rt {
namespace detail { // not API: the public-names check would name them

/// The whole of a small /proc file ("" when it cannot be read).
inline std::string kit_check_proc_file(long pid, const char* name)
{
    std::string text;
    const std::string path = "/proc/" + std::to_string(pid) + "/" + name;
    if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
        char buffer[4096];
        std::size_t n = 0;
        while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0)
            text.append(buffer, n);
        std::fclose(f);
    }
    return text;
}

/// The command line (NUL-separated) of the ctest test this process belongs to:
/// of the ancestor whose parent is ctest, which started it; "" if none is found.
inline std::string kit_check_test_command()
{
    long pid = long(::getpid());
    for (int depth = 0; depth < 64 && pid > 1; ++depth) {
        const std::string stat = kit_check_proc_file(pid, "stat");
        const std::size_t close = stat.rfind(')'); // after the command name, which may hold spaces
        if (close == std::string::npos)
            return "";
        long parent = 0;
        char state = 0;
        if (std::sscanf(stat.c_str() + close + 1, " %c %ld", &state, &parent) != 2)
            return "";
        if (kit_check_proc_file(parent, "comm") == "ctest\n")
            return kit_check_proc_file(pid, "cmdline");
        pid = parent;
    }
    return "";
}

/// With RT_KIT_TRACE set, appends "<stages> <test's command line in hex>" to
/// <folder>/<pid>.trace the first time this process asks about a stage.
inline void kit_check_trace(std::initializer_list<int> stages)
{
    static const char* const folder = std::getenv("RT_KIT_TRACE");
    if (folder == nullptr || *folder == '\0')
        return;
    static std::atomic<unsigned long> recorded{0};
    unsigned long mask = 0;
    for (const int stage : stages)
        if (stage >= 0 && stage < 64)
            mask |= 1ul << stage;
    // a load first: the exercises of a render are asked about once per pixel,
    // and a read-modify-write each time would bounce the line between threads
    if ((recorded.load(std::memory_order_relaxed) & mask) == mask || (recorded.fetch_or(mask) & mask) == mask)
        return;
    static const std::string command = kit_check_test_command();
    std::string line = std::to_string(mask) + " ";
    for (const unsigned char c : command) {
        const char* digits = "0123456789abcdef";
        line += digits[c >> 4];
        line += digits[c & 15];
    }
    line += "\n";
    const std::string path = std::string(folder) + "/" + std::to_string(long(::getpid())) + ".trace";
    // One write: the lines of threads do not mix. A trace that cannot be
    // written stops the process: its test then fails with nothing stripped,
    // and check_kit reruns such a test for every stage.
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd < 0 || ::write(fd, line.data(), line.size()) != ::ssize_t(line.size()))
        std::abort();
    ::close(fd);
}

inline bool kit_check_strips(std::initializer_list<int> stages)
{
    kit_check_trace(stages);
    static const unsigned long chosen = [] {
        unsigned long mask = 0;
        const char* text = std::getenv("RT_KIT_STRIP");
        while (text != nullptr && *text != '\0') {
            char* end = nullptr;
            const long stage = std::strtol(text, &end, 10);
            if (end == text)
                break;
            if (stage >= 0 && stage < 64)
                mask |= 1ul << stage;
            text = *end == ',' ? end + 1 : end;
        }
        return mask;
    }();
    for (const int stage : stages)
        if ((chosen >> stage) & 1ul)
            return true;
    return false;
}

} // namespace detail
} // namespace rt
