// Stage 07 - reflections: shading, shadows and mirrors, L += km raycolor(p, r)
// (include/rt/raytracer.hpp).
//
//     stage07_reflections scenes/mirrors.scene -o mirrors.png [--max-depth N]
#include <iostream>
#include <string>

#include <rt/raytracer.hpp>

#include "shaded_stage.hpp"

int main(int argc, char** argv)
{
    return stage::run("stage07_reflections", [&] {
        stage::arguments args(argc, argv);
        std::string scene_path, output = "reflections.png";
        int max_depth = -1;
        stage::pixel_request pixel;
        while (!args.done()) {
            const std::string arg = args.take();
            if (arg == "--help" || arg == "-h") {
                std::cout << "usage: stage07_reflections SCENE [-o OUTPUT] [--max-depth N]\n"
                             "Renders SCENE with shading, shadows and mirror reflections.\n"
                             "  -o OUTPUT        .png, .ppm or .pfm (default reflections.png)\n"
                             "  --max-depth N    mirror bounces, 0..64 (default: the scene's max_depth)\n"
                          << stage::pixel_help;
                return 0;
            } else if (arg == "-o") {
                output = args.value_of("-o");
            } else if (arg == "--max-depth") {
                const std::string text = args.value_of("--max-depth");
                const bool digits = !text.empty() && text.size() <= 2 && text.find_first_not_of("0123456789") == std::string::npos;
                if (!digits || std::stoi(text) > 64)
                    throw rt::error("--max-depth: expected a whole number from 0 to 64, found '" + text + "'");
                max_depth = std::stoi(text);
            } else if (arg == "--pixel" || arg == "--pixel-json") {
                stage::read_pixel(args, arg, pixel);
            } else if (!arg.empty() && arg[0] == '-') {
                throw rt::error("expected an option (-o, --max-depth, --pixel, --pixel-json, --help), found '" + arg +
                                "'; see --help");
            } else if (scene_path.empty()) {
                scene_path = arg;
            } else {
                throw rt::error("expected one scene file, found also '" + arg + "'; see --help");
            }
        }
        if (scene_path.empty())
            throw rt::error("expected a scene file, found none; see --help");
        stage::render_shaded(
            "stage07_reflections", scene_path, output, pixel, {true, false},
            [](const rt::scene& s, const auto& world, const rt::ray& r) { return rt::ray_color(s, world, r); },
            [&](rt::scene& s) {
                if (max_depth >= 0)
                    s.max_depth = max_depth;
            });
        return 0;
    });
}
