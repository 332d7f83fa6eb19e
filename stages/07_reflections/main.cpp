// Stage 07 - reflections: shading, shadows and mirrors, L += km raycolor(p, r)
// (include/rt/shading/raytracer.hpp).
//
//     stage07_reflections scenes/mirrors.scene -o mirrors.png [--max-depth N]
#include <iostream>
#include <optional>
#include <string>

#include <rt/shading/raytracer.hpp>

#include "shaded_stage.hpp"

int main(int argc, char** argv)
{
    return stage::run("stage07_reflections", [&] {
        stage::arguments args(argc, argv);
        std::string output = "reflections.png";
        int max_depth = -1;
        stage::pixel_request pixel;
        const std::string usage = std::string("usage: stage07_reflections SCENE [-o OUTPUT] [--max-depth N]\n"
                                              "Renders SCENE with shading, shadows and mirror reflections.\n"
                                              "  -o OUTPUT        .png, .ppm or .pfm (default reflections.png)\n"
                                              "  --max-depth N    mirror bounces, 0..64 (default: the scene's max_depth)\n") +
                                  stage::pixel_help;
        const std::optional<std::string> scene_path = stage::read_command_line(
            args, usage, "-o, --max-depth, --pixel, --pixel-json", [&](const std::string& arg) {
                if (arg == "--max-depth")
                    max_depth = int(stage::parse_integer(arg, args.value_of(arg), 0, 64));
                else
                    return stage::read_image_option(args, arg, output, pixel);
                return true;
            });
        if (!scene_path)
            return 0; // --help
        stage::render_shaded(
            "stage07_reflections", *scene_path, output, pixel, {true, false},
            [](const rt::scene& s, const auto& world, const rt::ray& r) { return rt::ray_color(s, world, r); },
            [&](rt::scene& s) {
                if (max_depth >= 0)
                    s.max_depth = max_depth;
            });
        return 0;
    });
}
