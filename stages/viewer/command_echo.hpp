// command_echo.hpp - the stage08_output command that writes the image the
// viewer shows (the save key prints it, `p` too), quoted for a POSIX shell.
#pragma once

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include <rt/core/decimal_text.hpp>
#include <rt/input/camera_statement.hpp>
#include <rt/output/encoding.hpp>

#include "progressive.hpp"

namespace viewer {

/// `text` as one shell word: unchanged when it is plain, else in single quotes.
inline std::string shell_word(const std::string& text)
{
    const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
        return std::isalnum(static_cast<unsigned char>(c)) || std::string("_./-=+:,@%").find(c) != std::string::npos;
    });
    if (plain)
        return text;
    std::string quoted = "'";
    for (char c : text)
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

/// The stage08_output arguments (without -o) that write `done` with `enc`.
inline std::vector<std::string> stage08_arguments(const std::string& input, const viewer::completed_image& done,
                                                  const rt::encoding& enc)
{
    const viewer::view& v = done.settings;
    if (v.path_traced)
        return {}; // command_line says why there is none
    auto number = [](double value) { return rt::exact_number_text(rt::real(value)); };
    std::vector<std::string> a = {input,
                                  "--width", std::to_string(v.width),
                                  "--height", std::to_string(v.height),
                                  "--camera", rt::camera_statement(v.cam),
                                  "--spp", std::to_string(done.pass.samples_per_pixel),
                                  "--sampler", rt::name_of(done.pass.sampler),
                                  "--filter", rt::name_of(v.reconstruction.kind),
                                  "--filter-radius", rt::exact_number_text(v.reconstruction.radius),
                                  "--max-depth", std::to_string(v.max_depth),
                                  "--seed", std::to_string(v.seed)};
    if (v.aov != rt::aov_kind::shaded) {
        a.insert(a.end(), {"--aov", rt::name_of(v.aov)});
    } else {
        a.insert(a.end(), {"--tonemap", rt::name_of(enc.tonemap), "--exposure", number(double(enc.exposure))});
        if (enc.transfer == rt::transfer_kind::gamma)
            a.insert(a.end(), {"--gamma", number(double(enc.gamma))});
    }
    return a;
}

inline std::string command_line(const std::vector<std::string>& arguments, const std::string& output)
{
    if (arguments.empty()) // a path-traced view: no program takes its camera and options
        return "(none: stage11_path_tracing renders a scene's own camera; the viewer's path-traced view has no "
               "command line)";
    std::string line = "stage08_output";
    for (const std::string& word : arguments)
        line += ' ' + shell_word(word);
    return line + " -o " + shell_word(output);
}

} // namespace viewer
