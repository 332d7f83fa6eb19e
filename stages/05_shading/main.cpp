// Stage 05 - shading: every pixel colored by Blinn-Phong (include/rt/shading/shading.hpp),
// every light visible (no shadows yet: that is stage 06).
//
//     stage05_shading scenes/shading.scene -o shading.png [--falloff]
#include <iostream>
#include <limits>
#include <optional>
#include <string>

#include <rt/shading/shading.hpp>

#include "shaded_stage.hpp"

int main(int argc, char** argv)
{
    return stage::run("stage05_shading", [&] {
        stage::arguments args(argc, argv);
        std::string output = "shading.png";
        stage::pixel_request pixel;
        rt::shading_options options;
        const std::string usage = std::string("usage: stage05_shading SCENE [-o OUTPUT] [--falloff] [--pixel I J]\n"
                                              "Renders SCENE with Blinn-Phong shading and no shadows.\n"
                                              "  -o OUTPUT        .png, .ppm or .pfm (default shading.png)\n"
                                              "  --falloff        point lights fall off as 1/r^2 (default: off, as in the book)\n") +
                                  stage::pixel_help;
        const std::optional<std::string> scene_path =
            stage::read_command_line(args, usage, "-o, --falloff, --pixel, --pixel-json", [&](const std::string& arg) {
                if (arg == "--falloff")
                    options.light_falloff = true;
                else
                    return stage::read_image_option(args, arg, output, pixel);
                return true;
            });
        if (!scene_path)
            return 0; // --help
        stage::render_shaded("stage05_shading", *scene_path, output, pixel, {false, options.light_falloff},
                             [&](const rt::scene& s, const auto& world, const rt::ray& r) {
                                 rt::hit_record hit;
                                 if (!world.closest_hit(r, 0, std::numeric_limits<rt::real>::infinity(), hit))
                                     return s.background;
                                 return rt::direct_lighting(
                                     s, hit, r.direction, [](const rt::light_sample&) { return true; }, options);
                             });
        return 0;
    });
}
