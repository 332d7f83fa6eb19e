// viewer_command.hpp - the viewer's command line: the render options it shares
// with stage08_output (render_arguments.hpp), -o, --script and --timeout, and
// the help text with the mouse and key controls.
#pragma once

#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include <rt/core/error.hpp>

#include "render_arguments.hpp"
#include "stage_main.hpp"

namespace viewer {

inline const char* const controls =
    "Mouse: left drag orbits around the look-at point, right (or middle, or shift + left)\n"
    "drag pans, the wheel zooms.\n"
    "Keys:  1 shaded  2 normals  3 depth  4 position  5 ray directions  6 path traced (stage 11)\n"
    "       m next sampler (auto, center, grid, random, jittered, halton)\n"
    "       f next filter (box, tent, gaussian, mitchell)\n"
    "       ] [ samples per pixel x2 / /2      . , max depth +1 / -1\n"
    "       = - exposure +/- 1/2 stop          t next tone map\n"
    "       r reset the camera   s save the image (and print its stage08_output command)\n"
    "       p print that command   h this help   q or Escape quit\n"
    "       i ray inspector: click a pixel to see its rays (camera white, shadow yellow or red\n"
    "         when blocked, reflection cyan, refraction magenta) and read its story on stderr\n";

inline const std::string usage = std::string("usage: viewer (SCENE | MODEL.obj) [options]\n"
                                      "Renders a scene file or a bare OBJ model in a window, a coarse preview first,\n"
                                      "then the full image at 1, 4, 16 ... samples per pixel, and restarts whenever\n"
                                      "the camera or a setting changes. The options are stage08_output's:\n") +
                          stage::render_options_usage +
                          "  -o OUTPUT             where the save key writes (.png, .ppm or .pfm; default render.png)\n"
                          "  --script TEXT|@FILE   scripted input (docs/viewer.md): orbit, pan, zoom, key, click,\n"
                          "                        wait, sleep, screenshot, title, save, args, story, quit\n"
                          "  --timeout SECONDS     give up (exit 1) after this long (default: never)\n"
                          "  --help                this text\n\n" +
                          controls;

struct settings {
    stage::render_settings render;
    std::string output = "render.png";
    std::string script;
    std::string script_name = "--script";
    double timeout = 0;
};

/// The settings of the command line; nullopt for --help (the usage is printed).
inline std::optional<settings> read_arguments(stage::arguments& args)
{
    settings s;
    const std::optional<std::string> input = stage::read_command_line(
        args, usage, "-o, the render options, --script, --timeout",
        [&](const std::string& arg) {
            if (arg == "-o") {
                s.output = args.value_of(arg);
            } else if (stage::read_render_option(args, arg, s.render)) {
                // shared with stage08_output
            } else if (arg == "--script") {
                s.script = args.value_of(arg);
                if (!s.script.empty() && s.script[0] == '@') {
                    s.script_name = s.script.substr(1);
                    std::ifstream in(stage::file_argument(s.script_name), std::ios::binary);
                    if (!in)
                        throw rt::error(rt::source_location{s.script_name},
                                        "expected a readable script file, found none; check the path after '@'");
                    s.script.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
                }
            } else if (arg == "--timeout") {
                s.timeout = stage::parse_number(arg, args.value_of(arg), 0, 86400, true);
            } else {
                return false;
            }
            return true;
        },
        "a scene or OBJ file");
    if (!input)
        return std::nullopt;
    s.render.input = *input;
    return s;
}

} // namespace viewer
