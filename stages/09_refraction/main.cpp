// Stage 09 - refraction: glass, L = k (R raycolor(p, r) + (1 - R) raycolor(p, t))
// (include/rt/shading/dielectric.hpp, include/rt/shading/refraction.hpp).
//
//     stage09_refraction scenes/glass.scene -o glass.png [--max-depth N]
#include <iostream>
#include <optional>
#include <string>

#include <rt/shading/dielectric.hpp>

#include "shaded_stage.hpp"

int main(int argc, char** argv)
{
    return stage::run("stage09_refraction", [&] {
        stage::arguments args(argc, argv);
        std::string output = "refraction.png";
        int max_depth = -1;
        stage::pixel_request pixel;
        const std::string usage = std::string("usage: stage09_refraction SCENE [-o OUTPUT] [--max-depth N]\n"
                                              "Renders SCENE with shading, shadows, mirrors and glass.\n"
                                              "  -o OUTPUT        .png, .ppm or .pfm (default refraction.png)\n"
                                              "  --max-depth N    bounces, 0..64 (default: the scene's max_depth)\n") +
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
            "stage09_refraction", *scene_path, output, pixel, {true, false},
            [](const rt::scene& s, const auto& world, const rt::ray& r) { return rt::ray_color_glass(s, world, r); },
            [&](rt::scene& s) {
                if (max_depth >= 0)
                    s.max_depth = max_depth;
            });
        return 0;
    });
}
