// Stage 06 - shadows: Blinn-Phong with a shadow ray to each light
// (include/rt/shading/shadows.hpp), started past the hit point's rounding error
// (light_visible: spawn_ray_to) or, for comparison, with the textbook's fixed
// epsilon.
//
//     stage06_shadows scenes/shadows.scene -o shadows.png [--offset robust|fixed] [--epsilon E]
#include <iostream>
#include <limits>
#include <optional>
#include <string>

#include <rt/shading/shading.hpp>
#include <rt/shading/shadows.hpp>

#include "shaded_stage.hpp"

int main(int argc, char** argv)
{
    return stage::run("stage06_shadows", [&] {
        stage::arguments args(argc, argv);
        std::string output = "shadows.png", offset = "robust";
        rt::real epsilon = rt::real(1e-4);
        stage::pixel_request pixel;
        const std::string usage =
            std::string("usage: stage06_shadows SCENE [-o OUTPUT] [--offset robust|fixed] [--epsilon E]\n"
                        "Renders SCENE with Blinn-Phong shading and shadow rays.\n"
                        "  -o OUTPUT        .png, .ppm or .pfm (default shadows.png)\n"
                        "  --offset robust  start shadow rays past the hit point's rounding error (spawn_ray_to,\n"
                        "                   PBR 3rd ed. sec. 3.9.5: what light_visible does; default)\n"
                        "  --offset fixed   start them at the hit point and skip hits closer than E\n"
                        "  --epsilon E      the fixed epsilon (default 1e-4)\n") +
            stage::pixel_help;
        const std::optional<std::string> scene_path = stage::read_command_line(
            args, usage, "-o, --offset, --epsilon, --pixel, --pixel-json", [&](const std::string& arg) {
                if (arg == "--offset")
                    offset = stage::parse_choice(arg, args.value_of(arg), {"robust", "fixed"});
                else if (arg == "--epsilon")
                    epsilon = rt::real(stage::parse_number(arg, args.value_of(arg), 0, 1e30));
                else
                    return stage::read_image_option(args, arg, output, pixel);
                return true;
            });
        if (!scene_path)
            return 0; // --help
        const bool robust = offset == "robust";
        stage::render_shaded(
            "stage06_shadows", *scene_path, output, pixel, {true, false},
            [&](const rt::scene& s, const auto& world, const rt::ray& r) {
                rt::hit_record hit;
                if (!world.closest_hit(r, 0, std::numeric_limits<rt::real>::infinity(), hit))
                    return s.background;
                return rt::direct_lighting(s, hit, r.direction, [&](const rt::light_sample& sample) {
                    return robust ? rt::light_visible(world, hit, sample)
                                  : rt::light_visible_fixed_epsilon(world, hit, sample, epsilon);
                });
            });
        return 0;
    });
}
