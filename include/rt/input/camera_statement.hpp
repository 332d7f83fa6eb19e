// camera_statement.hpp - the scene file's camera statement (stage 01).
//
//     camera perspective|orthographic [eye x y z] [look_at x y z] [up x y z]
//                                     [fov degrees] [window l r b t] [focal d]
//
// parse_camera is the stage-01 exercise: read the statement's options into a
// camera (camera_model.hpp) and refuse one that describes no camera. The
// words of the statement come from scene_statement.hpp; docs/scene-format.md
// gives the defaults, docs/stages/01-load-scene.md the rules and their messages.
//
//     rt::camera cam = rt::parse_camera_statement("perspective eye 0 1 5 fov 40");
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "../scene/camera_model.hpp"
#include "../core/config.hpp"
#include "../core/error.hpp"
#include "scene_statement.hpp"
#include "text_line.hpp"
#include "../core/vec.hpp"

namespace rt {


/// Reads a camera statement into `cam`:
///     camera perspective|orthographic [eye x y z] [look_at x y z] [up x y z]
///                                     [fov degrees] [window l r b t] [focal d]
/// and checks that it describes a camera: e differs from look_at, up is not
/// parallel to the view direction, fov in (0, 180), l < r, b < t, d > 0.
inline void parse_camera(statement& line, camera& cam)
{
    // RT_EXERCISE_BEGIN(stage01: load the camera)
    const std::string kind = line.word("a camera type (perspective or orthographic)");
    if (kind == "perspective")
        cam.kind = projection::perspective;
    else if (kind == "orthographic")
        cam.kind = projection::orthographic;
    else
        throw make_error(line.last(), "a camera type (perspective or orthographic)", found_text(kind),
                         nearest_hint(kind, {"perspective", "orthographic"}));

    source_location view_at = line.line_start(), up_at = line.line_start();
    line.options({"eye", "look_at", "up", "fov", "window", "focal"}, [&](const std::string& option) {
        const source_location where = line.here();
        if (option == "eye") {
            cam.eye = line.vector("eye");
            view_at = where;
        } else if (option == "look_at") {
            cam.look_at = line.vector("look_at");
            view_at = where;
        } else if (option == "up") {
            cam.up = line.direction("up");
            up_at = where;
        } else if (option == "fov") {
            const real fov = line.number("fov");
            if (!(fov > 0 && fov < 180))
                throw make_error(where, "a field of view between 0 and 180 degrees", detail::short_number(double(fov)));
            if (cam.kind == projection::orthographic)
                throw make_error(where, "a window for an orthographic camera", "fov",
                                 "fov applies to perspective cameras only; use window l r b t");
            cam.fov_degrees = fov;
        } else if (option == "window") {
            window win;
            win.l = line.number("window l");
            win.r = line.number("window r");
            win.b = line.number("window b");
            win.t = line.number("window t");
            if (!(win.l < win.r) || !(win.b < win.t))
                throw make_error(where, "a window with l < r and b < t", "an empty window");
            cam.plane = win;
        } else { // focal
            cam.focal_distance = line.number("focal distance");
            if (!(cam.focal_distance > 0))
                throw make_error(where, "a positive focal distance", detail::short_number(double(cam.focal_distance)));
        }
    });
    if (cam.fov_degrees && cam.plane)
        throw make_error(line.line_start(), "either fov or window", "both", "give one of them");
    const vec3 view = cam.look_at - cam.eye;
    if (glm::dot(view, view) == real(0))
        throw make_error(view_at, "a look_at point different from the eye", "the same point",
                         "the camera needs a direction to look in");
    // The frame normalises look_at - eye, which squares its length: past about
    // 1e19 in float that square overflows and every ray would be NaN.
    if (!std::isfinite(glm::dot(view, view)))
        throw make_error(view_at, "an eye within about 1e19 of look_at (the square of the distance must fit rt::real)",
                         "a distance whose square overflows",
                         "move the scene nearer the origin, or build with -DRT_USE_DOUBLE=ON");
    // the frame normalises up x w too: |up|^2 must be a normal, finite number
    const real up_squared = glm::dot(cam.up, cam.up);
    if (!(up_squared >= std::numeric_limits<real>::min() && std::isfinite(up_squared)))
        throw make_error(up_at, "an up vector whose squared length fits rt::real (a length from about 1e-19 to 1e19)",
                         "one of length " + detail::short_number(double(glm::length(glm::dvec3(cam.up)))),
                         "the length of up does not matter: use 0 1 0 or 0 0 1");
    // up and the view direction scaled to a largest coordinate of 1 first, so
    // that neither a huge nor a tiny vector overflows the test (the test is
    // sin^2 of their angle > 1e-12)
    auto scaled = [](const vec3& a) {
        return a / std::max(std::fabs(a.x), std::max(std::fabs(a.y), std::fabs(a.z)));
    };
    const vec3 up = scaled(cam.up), ahead = scaled(view);
    const vec3 side = glm::cross(up, ahead);
    if (!(glm::dot(side, side) > real(1e-12) * glm::dot(ahead, ahead) * glm::dot(up, up)))
        throw make_error(up_at, "an up vector not parallel to the view direction", "a parallel one",
                         "choose an up vector that differs from look_at - eye, such as 0 1 0 or 0 0 1");
    // RT_EXERCISE_END
}

/// A camera from the arguments of a `camera` statement (what camera_statement
/// writes), checked as the scene loader checks it; `name` starts its messages.
/// Columns in messages count in `arguments`.
inline camera parse_camera_statement(const std::string& arguments, const std::string& name = "--camera")
{
    std::vector<token> tokens = detail::tokenize(arguments, source_location{name, 1});
    tokens.insert(tokens.begin(), token{"camera", 0});
    statement line(name, 1, std::move(tokens), int(arguments.size()) + 1);
    camera cam;
    parse_camera(line, cam);
    line.end();
    return cam;
}

} // namespace rt
