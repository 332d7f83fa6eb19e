// Stage 07 - reflections: shading, shadows and mirrors, L += km raycolor(p, r)
// (include/rt/shading/raytracer.hpp).
//
//     stage07_reflections scenes/mirrors.scene -o mirrors.png [--max-depth N]
#include <optional>
#include <string>

#include <rt/shading/raytracer.hpp>

#include "shaded_stage.hpp"

namespace {

const std::string usage = std::string("usage: stage07_reflections SCENE [-o OUTPUT] [--max-depth N]\n"
                                      "Renders SCENE with shading, shadows and mirror reflections.\n"
                                      "  -o OUTPUT        .png, .ppm or .pfm (default reflections.png)\n"
                                      "  --max-depth N    mirror bounces, 0..64 (default: the scene's max_depth)\n") +
                          stage::pixel_help;

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage07_reflections", [&] {
        stage::arguments args(argc, argv);
        const std::optional<stage::depth_command> c = stage::read_depth_command(args, usage, "reflections.png");
        if (!c)
            return 0; // --help
        stage::render_shaded(
            "stage07_reflections", c->scene, c->output, c->pixel, {true, false},
            [](const rt::scene& s, const auto& world, const rt::ray& r) { return rt::ray_color(s, world, r); },
            c->adjust());
        return 0;
    });
}
