// Stage 09 - refraction: glass, L = k (R raycolor(p, r) + (1 - R) raycolor(p, t))
// (include/rt/shading/dielectric.hpp, include/rt/shading/refraction.hpp).
//
//     stage09_refraction scenes/glass.scene -o glass.png [--max-depth N]
#include <optional>
#include <string>

#include <rt/shading/dielectric.hpp>

#include "shaded_stage.hpp"

namespace {

const std::string usage = std::string("usage: stage09_refraction SCENE [-o OUTPUT] [--max-depth N]\n"
                                      "Renders SCENE with shading, shadows, mirrors and glass.\n"
                                      "  -o OUTPUT        .png, .ppm or .pfm (default refraction.png)\n"
                                      "  --max-depth N    bounces, 0..64 (default: the scene's max_depth)\n") +
                          stage::pixel_help;

} // namespace

int main(int argc, char** argv)
{
    return stage::run("stage09_refraction", [&] {
        stage::arguments args(argc, argv);
        const std::optional<stage::depth_command> c = stage::read_depth_command(args, usage, "refraction.png");
        if (!c)
            return 0; // --help
        stage::render_shaded(
            "stage09_refraction", c->scene, c->output, c->pixel, {true, false},
            [](const rt::scene& s, const auto& world, const rt::ray& r) { return rt::ray_color_glass(s, world, r); },
            c->adjust());
        return 0;
    });
}
