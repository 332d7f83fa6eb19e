// viewer - watch a render form, move the camera, save what you see (SDL2).
//
//     viewer scenes/showcase.scene
//     viewer ../shared/meshes/stanford-bunny.obj --aov rays --spp 16
//
// The viewer holds no rendering logic: the scene, the camera's rays and the
// radiance function come from rt/rendering/render_setup.hpp and the options from
// stages/common/render_arguments.hpp, exactly as in stage08_output; the
// progressive loop (progressive.hpp) calls rt::render on crops, and the window
// shows the float image through rt::encode_color (encoding.hpp). So every
// finished level on screen is the image stage08_output writes for the same
// camera and settings, and the save key prints that command.
// Controls, options and the test: docs/viewer.md.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <SDL.h>

#include <rt/rendering/scene_input.hpp>
#include <rt/scene/scene.hpp>
#include <rt/system/atomic_file.hpp>

#include "app.hpp"
#include "app_draw.hpp"
#include "app_input.hpp"
#include "app_script.hpp"
#include "stage_main.hpp"
#include "viewer_command.hpp"

int main(int argc, char** argv)
{
    return stage::run("viewer", [&] {
        stage::arguments args(argc, argv);
        const std::optional<viewer::settings> arguments = viewer::read_arguments(args);
        if (!arguments)
            return 0; // --help
        const viewer::settings& set = *arguments;
        rt::check_image_output(stage::file_argument(set.output)); // the save key must not fail at the end
        // script errors before the window opens; the files a script writes are outputs too
        std::vector<std::filesystem::path> outputs{stage::file_argument(set.output)};
        for (const viewer::script_command& c : viewer::parse_script(set.script, set.script_name))
            if (c.name == "save" || c.name == "screenshot" || c.name == "title" || c.name == "args" ||
                c.name == "story")
                outputs.push_back(stage::file_argument(c.arguments[0]));
        const bool obj = rt::has_obj_extension(stage::file_argument(set.render.input));
        stage::check_input_and_outputs(set.render.input, obj ? "an OBJ file" : "a scene file", outputs);
        rt::scene scene = stage::load_render_input(set.render);
        // its OBJ and MTL files too
        rt::check_not_input(outputs, rt::files_read(stage::file_argument(set.render.input), scene));
        const viewer::sdl_session sdl;
        // without a display SDL falls back to a driver that shows nothing: fine for a script, not for a person
        const std::string driver = SDL_GetCurrentVideoDriver() ? SDL_GetCurrentVideoDriver() : "";
        if ((driver == "offscreen" || driver == "dummy") && set.script.empty())
            throw rt::error("cannot open a window: no display (SDL chose its '" + driver +
                            "' video driver, which shows nothing); set DISPLAY, or run under xvfb-run");
        viewer::app window(set, std::move(scene));
        return window.run();
    });
}
