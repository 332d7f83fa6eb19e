// bench.hpp - what every benchmark program shares: its command line, the
// description of the machine, timing, a parallel loop over blocks (rt::parallel_for)
// and the CSV it writes.
//
// Every program takes
//     --quick         tiny sizes (CI runs this so the benchmarks never rot)
//     --out DIR       where the CSV goes (default: the current folder)
//     --shared DIR    the shared test-data folder (default: ../shared beside the source tree)
// and writes one CSV whose first lines are comments ("# key: value") that
// describe the machine, the build and the command, so that a chart made from
// it can say where its numbers come from. No timing is ever asserted.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <rt/system/atomic_file.hpp>
#include <rt/core/config.hpp>
#include <rt/core/error.hpp>
#include <rt/system/parallel.hpp>

#include "command_line.hpp" // stages/common

#if defined(RT_BENCH_HAS_ACCELERATOR)
#include <rt/bvh/accelerator.hpp> // the BVH path of the machine line
#endif

#ifndef RT_BENCH_FLAGS
#define RT_BENCH_FLAGS "unknown"
#endif
#ifndef RT_BENCH_BUILD_TYPE
#define RT_BENCH_BUILD_TYPE "unknown"
#endif
#ifndef RT_BENCH_SHARED_DIR
#define RT_BENCH_SHARED_DIR "../shared"
#endif
#ifndef RT_BENCH_SOURCE_DIR
#define RT_BENCH_SOURCE_DIR "."
#endif

namespace bench {

struct options {
    bool quick = false;
    std::filesystem::path out = ".";
    std::filesystem::path shared = RT_BENCH_SHARED_DIR;
    std::string command;  ///< the command line, for the CSV's header
    std::vector<std::string> extra;  ///< arguments the program reads itself
};

/// The benchmark's command line (stages/common/command_line.hpp, the parser
/// every rt program uses); words that are not options go to `extra`. Exits 0
/// after --help.
inline options parse_options(int argc, char** argv, const char* usage)
{
    options o;
    stage::arguments args(argc, argv);
    o.command = args.command();
    const std::string help = std::string(usage) + "\n  --quick       tiny sizes (seconds, for CI)\n" +
                             "  --out DIR     folder for the CSV (default .)\n" +
                             "  --shared DIR  the shared test data (default " RT_BENCH_SHARED_DIR ")\n";
    const auto operands = stage::read_operands(args, help, "--quick, --out, --shared", [&](const std::string& a) {
        if (a == "--quick")
            o.quick = true;
        else if (a == "--out")
            o.out = args.value_of(a);
        else if (a == "--shared")
            o.shared = args.value_of(a);
        else
            return false;
        return true;
    });
    if (!operands)
        std::exit(0); // --help
    o.extra = *operands;
    return o;
}

/// The first "model name" line of /proc/cpuinfo (Linux), or "unknown".
inline std::string cpu_model()
{
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            const auto colon = line.find(':');
            if (colon != std::string::npos) {
                std::string name = line.substr(colon + 1);
                name.erase(0, name.find_first_not_of(" \t"));
                return name;
            }
        }
    return "unknown";
}

/// The SIMD extensions the CPU reports that matter for ray tracing kernels.
inline std::string cpu_simd()
{
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("flags", 0) == 0) {
            std::string found;
            for (const char* flag : {"sse4_2", "avx", "avx2", "fma", "avx512f"}) {
                const std::string needle = " " + std::string(flag) + " ";
                if ((line + " ").find(needle) != std::string::npos)
                    found += (found.empty() ? "" : "+") + std::string(flag);
            }
            return found.empty() ? "none" : found;
        }
    return "unknown";
}

inline std::string compiler()
{
#if defined(__clang__)
    return "clang++ " __clang_version__;
#elif defined(__GNUC__)
    return "g++ " __VERSION__;
#else
    return "unknown compiler";
#endif
}

inline unsigned hardware_threads()
{
    return unsigned(rt::thread_count(0));
}

/// One line that says where the numbers come from.
inline std::string machine_line()
{
    std::string flags = RT_BENCH_FLAGS;
#if defined(RT_BENCH_CONTRACT) // built without -ffp-contract=off (bench/CMakeLists.txt)
    const std::string off = "-ffp-contract=off";
    const auto at = flags.find(off);
    if (at != std::string::npos)
        flags.replace(at, off.size(), "-ffp-contract=fast");
#endif
    std::ostringstream s;
    s << cpu_model() << ", " << hardware_threads() << " hardware threads, " << cpu_simd() << "; " << compiler()
      << ", " << RT_BENCH_BUILD_TYPE << " " << flags << "; rt::real = "
      << (sizeof(rt::real) == 4 ? "float" : "double");
#if defined(RT_BENCH_HAS_ACCELERATOR)
    // which walk rt::accelerator takes here: a build without -march=native
    // picks it at run time (include/rt/bvh/dispatch.hpp)
    s << "; BVH path " << rt::describe(rt::accelerator::automatic_path())
      << (rt::accelerator::dispatches ? " (dispatched)" : "");
#endif
    return s.str();
}

using clock = std::chrono::steady_clock;

inline double seconds_since(clock::time_point start)
{
    return std::chrono::duration<double>(clock::now() - start).count();
}

/// The shortest of `repeats` runs of `work` (at least one), in seconds. The
/// machine is shared: the minimum is the run least disturbed by other work.
template <class Work>
double best_time(int repeats, Work&& work)
{
    double best = 1e300;
    for (int k = 0; k < std::max(1, repeats); ++k) {
        const auto start = clock::now();
        work();
        best = std::min(best, seconds_since(start));
    }
    return best;
}

/// Calls body(begin, end) on blocks of [0, count) from `threads` threads
/// (rt::parallel_for over the blocks: handed out through an atomic counter, so
/// a slow block does not hold the others back).
template <class Body>
void parallel_blocks(std::size_t count, unsigned threads, std::size_t block, Body&& body)
{
    rt::parallel_for((count + block - 1) / block, int(threads), [&](std::size_t k, int) {
        body(k * block, std::min(count, (k + 1) * block));
    });
}

/// Rows of a CSV, written at the end in one go (atomically: a killed run
/// leaves the previous file, not half a table).
class csv {
public:
    csv(std::string experiment, std::vector<std::string> columns)
        : experiment_(std::move(experiment)), columns_(std::move(columns))
    {
    }

    /// Adds a comment line "# key: value" below the machine description.
    void note(const std::string& key, const std::string& value) { notes_.push_back(key + ": " + value); }

    class row_builder {
    public:
        explicit row_builder(std::vector<std::string>& cells) : cells_(cells) {}
        row_builder& operator<<(const std::string& text)
        {
            cells_.push_back(text);
            return *this;
        }
        row_builder& operator<<(const char* text) { return *this << std::string(text); }
        template <class Number>
        row_builder& operator<<(Number value)
        {
            std::ostringstream s;
            s << std::setprecision(7) << value;
            cells_.push_back(s.str());
            return *this;
        }

    private:
        std::vector<std::string>& cells_;
    };

    row_builder row()
    {
        rows_.emplace_back();
        return row_builder(rows_.back());
    }

    void write(const options& o, const std::string& file_name) const
    {
        std::filesystem::create_directories(o.out);
        const std::filesystem::path path = o.out / file_name;
        rt::write_atomically(path, [&](std::ostream& out) {
            out << "# experiment: " << experiment_ << '\n'
                << "# machine: " << machine_line() << '\n'
                << "# command: " << o.command << '\n'
                << "# mode: " << (o.quick ? "quick (tiny sizes: for CI, not for conclusions)" : "full") << '\n';
            for (const std::string& n : notes_)
                out << "# " << n << '\n';
            for (std::size_t k = 0; k < columns_.size(); ++k)
                out << (k ? "," : "") << columns_[k];
            out << '\n';
            for (const auto& cells : rows_) {
                if (cells.size() != columns_.size())
                    throw rt::error("bench: a row of " + file_name + " has " + std::to_string(cells.size()) +
                                    " cells for " + std::to_string(columns_.size()) + " columns");
                for (std::size_t k = 0; k < cells.size(); ++k)
                    out << (k ? "," : "") << cells[k];
                out << '\n';
            }
        });
        std::cout << "wrote " << path.string() << " (" << rows_.size() << " rows)\n";
    }

private:
    std::string experiment_;
    std::vector<std::string> columns_;
    std::vector<std::string> notes_;
    std::vector<std::vector<std::string>> rows_;
};

/// Keeps a value alive so that the compiler cannot drop the work that made it.
template <class T>
void keep(const T& value)
{
    asm volatile("" : : "g"(&value) : "memory");
}

/// main's body: one line on stderr and exit code 1 on any error.
template <class Body>
int run(const char* program, Body&& body)
{
    try {
        return body();
    } catch (const std::exception& e) {
        std::cerr << program << ": " << e.what() << '\n';
        return 1;
    }
}

} // namespace bench
