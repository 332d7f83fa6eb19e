// progress.hpp - the progress bar and the summary line of a render.
//
// Nothing here goes to stdout: stdout carries only what a user asked for. The
// bar is drawn on stderr, and only when stderr is a terminal (a log file or a
// pipe would fill with carriage returns); the one-line summary at the end is
// for everyone. The terminal test is the one non-portable call of the
// renderer, made by platform.hpp: POSIX isatty, Windows _isatty, and "not a
// terminal" where neither exists.
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>

#include "../system/platform.hpp"
#include "renderer.hpp"

namespace rt {

namespace detail {

/// True when stderr is a terminal (where a progress bar can redraw itself).
inline bool stderr_is_terminal()
{
    return detail::terminal_on_stderr();
}

/// A duration for people: "0.42 s", "12.3 s", "2 min 05 s", "1 h 02 min".
inline std::string format_duration(double seconds)
{
    std::ostringstream out;
    if (!(seconds >= 0))
        seconds = 0;
    if (seconds < 10) {
        out << std::fixed << std::setprecision(2) << seconds << " s";
    } else if (seconds < 60) {
        out << std::fixed << std::setprecision(1) << seconds << " s";
    } else if (seconds < 3600) {
        const auto whole = std::int64_t(seconds + 0.5);
        out << whole / 60 << " min " << std::setw(2) << std::setfill('0') << whole % 60 << " s";
    } else {
        const auto minutes = std::int64_t(seconds / 60 + 0.5);
        out << minutes / 60 << " h " << std::setw(2) << std::setfill('0') << minutes % 60 << " min";
    }
    return out.str();
}

/// A count with an SI prefix and three significant digits: "950", "12.3 k", "4.56 M", "1.20 G".
inline std::string format_count(double count)
{
    const char* prefixes[] = {"", " k", " M", " G", " T"};
    int p = 0;
    while (count >= 999.5 && p < 4) {
        count /= 1000;
        ++p;
    }
    std::ostringstream out;
    const int decimals = p == 0 ? 0 : count < 9.995 ? 2 : count < 99.95 ? 1 : 0;
    out << std::fixed << std::setprecision(decimals) << count << prefixes[p];
    return out.str();
}

/// "[#######.............]  P%  elapsed E s  ETA T s  R Mrays/s", each letter a number
inline std::string progress_line(const render_progress& p, int bar_width = 24)
{
    const double fraction = p.pixels_total > 0 ? double(p.pixels_done) / double(p.pixels_total) : 1.0;
    const int filled = int(fraction * bar_width);
    std::ostringstream out;
    out << '[' << std::string(std::size_t(filled), '#') << std::string(std::size_t(bar_width - filled), '.') << "] "
        << std::setw(3) << int(fraction * 100) << "%  elapsed " << format_duration(p.seconds) << "  ETA ";
    if (p.pixels_done > 0)
        out << format_duration(p.seconds * double(p.pixels_total - p.pixels_done) / double(p.pixels_done));
    else
        out << '?';
    if (p.seconds > 0)
        out << "  " << format_count(double(p.rays) / p.seconds) << "rays/s";
    return out.str();
}

} // namespace detail

/// "rendered 640x360 at 16 spp on 2 threads: N Mrays in T s (R Mrays/s)", N, T and R numbers
inline std::string summary_line(const render_stats& s)
{
    const double rays = double(s.camera_rays + s.extra_rays);
    std::ostringstream out;
    out << "rendered " << s.width << 'x' << s.height << " at " << s.samples_per_pixel << " spp on " << s.threads
        << (s.threads == 1 ? " thread: " : " threads: ") << detail::format_count(rays) << "rays in "
        << detail::format_duration(s.seconds);
    if (s.seconds > 0)
        out << " (" << detail::format_count(rays / s.seconds) << "rays/s)";
    return out.str();
}

/// Redraws progress_line on one terminal line; does nothing when disabled.
class progress_bar {
public:
    explicit progress_bar(std::ostream& out, bool enabled = detail::stderr_is_terminal()) : out_(&out), enabled_(enabled) {}

    void update(const render_progress& p)
    {
        if (!enabled_)
            return;
        const std::string line = detail::progress_line(p);
        const std::size_t pad = shown_ > line.size() ? shown_ - line.size() : 0;
        *out_ << '\r' << line << std::string(pad, ' ') << std::flush;
        shown_ = line.size();
    }

    /// Clears the bar's line, so the summary can take it.
    void finish()
    {
        if (enabled_ && shown_ > 0)
            *out_ << '\r' << std::string(shown_, ' ') << '\r' << std::flush;
        shown_ = 0;
    }

    /// A callback for rt::render that draws on this bar (which must outlive the render).
    progress_callback callback()
    {
        return [this](const render_progress& p) { update(p); };
    }

private:
    std::ostream* out_;
    bool enabled_;
    std::size_t shown_ = 0;
};

} // namespace rt
