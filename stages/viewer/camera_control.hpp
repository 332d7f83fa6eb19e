// camera_control.hpp - the viewer's mouse controls as changes of an rt::camera:
// orbit around the look-at point, pan in the image plane, zoom (no SDL here).
//
// Mouse moves are in window pixels, x to the right and y DOWN (as SDL reports
// them). The controls "grab the scene": what is under the cursor follows it.
#pragma once

#include <algorithm>
#include <cmath>

#include <rt/camera/camera.hpp>
#include <rt/core/vec.hpp>

namespace viewer {

/// Degrees of orbit per pixel of mouse movement.
constexpr rt::real orbit_degrees_per_pixel = rt::real(0.4);
/// One wheel step scales the distance to the look-at point (or an orthographic window) by this.
constexpr rt::real zoom_step = rt::real(0.9);
/// The orbit keeps the view direction at least this far from the up vector.
constexpr rt::real pole_margin_degrees = 1;

/// v rotated by `angle` radians about the unit axis k (right-handed), by
/// Rodrigues' rotation formula (O. Rodrigues, 1840; e.g. Wolfram MathWorld,
/// "Rodrigues' Rotation Formula"):
///     v' = v cos(a) + (k x v) sin(a) + k (k . v)(1 - cos(a))
inline rt::vec3 rotate_about(const rt::vec3& v, const rt::vec3& k, rt::real angle)
{
    const rt::real c = std::cos(angle), s = std::sin(angle);
    return v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (rt::real(1) - c));
}

/// Orbits the eye around look_at: dx pixels turn it about the up vector (the
/// scene turns with the mouse), dy pixels tilt it over the scene (dragging
/// down shows the scene more from above). The distance to look_at and the up
/// vector are kept; the tilt stops pole_margin_degrees short of the up vector.
inline rt::camera orbit(rt::camera cam, rt::real dx, rt::real dy)
{
    const rt::real pi = rt::real(3.14159265358979323846);
    const rt::real per_pixel = orbit_degrees_per_pixel * pi / 180;
    const rt::vec3 up = glm::normalize(cam.up);
    rt::vec3 offset = cam.eye - cam.look_at;
    const rt::real distance = glm::length(offset);
    // turn about the up vector: dragging right moves the eye to the left of the scene
    offset = rotate_about(offset, up, -dx * per_pixel);
    // tilt: the angle between the offset and up, kept inside (margin, pi - margin)
    const rt::real polar = std::acos(std::clamp(glm::dot(offset, up) / distance, rt::real(-1), rt::real(1)));
    const rt::real margin = pole_margin_degrees * pi / 180;
    const rt::real target = std::clamp(polar - dy * per_pixel, margin, pi - margin);
    // about up x offset (the camera's u direction), a positive angle turns the offset away from up
    const rt::vec3 side = glm::cross(up, offset);
    const rt::real side_length = glm::length(side);
    if (side_length > 0)
        offset = rotate_about(offset, side / side_length, target - polar);
    // rotations keep the length up to rounding; restore it exactly where it matters
    offset *= distance / glm::length(offset);
    cam.eye = cam.look_at + offset;
    return cam;
}

/// World units per pixel in the plane through look_at, parallel to the image,
/// for an image ny pixels high.
inline rt::real units_per_pixel(const rt::camera& cam, int nx, int ny)
{
    const rt::window win = rt::effective_window(cam, nx, ny);
    const rt::real window_height = win.t - win.b;
    if (cam.kind == rt::projection::orthographic)
        return window_height / rt::real(ny);
    // similar triangles: the window at focal distance d, the plane at distance |eye - look_at|
    return window_height / rt::real(ny) * glm::length(cam.eye - cam.look_at) / cam.focal_distance;
}

/// Moves eye and look_at together in the image plane so that the point at
/// look_at's depth follows the mouse by (dx, dy) pixels.
inline rt::camera pan(rt::camera cam, rt::real dx, rt::real dy, int nx, int ny)
{
    const rt::frame f = rt::make_frame(cam.eye, cam.look_at, cam.up);
    const rt::real scale = units_per_pixel(cam, nx, ny);
    // the scene moves right (+u on screen) when the camera moves left; y grows downwards on screen
    const rt::vec3 move = -dx * scale * f.u + dy * scale * f.v;
    cam.eye += move;
    cam.look_at += move;
    return cam;
}

/// Zooms by `steps` wheel steps (positive: closer). A perspective camera moves
/// its eye along the view direction, scaling its distance to look_at by
/// zoom_step^steps; an orthographic camera scales its window about its centre.
inline rt::camera zoom(rt::camera cam, rt::real steps, int nx, int ny)
{
    const rt::real factor = std::pow(zoom_step, steps);
    if (cam.kind == rt::projection::orthographic) {
        const rt::window win = rt::effective_window(cam, nx, ny);
        const rt::real cu = (win.l + win.r) / 2, cv = (win.b + win.t) / 2;
        cam.plane = rt::window{cu + (win.l - cu) * factor, cu + (win.r - cu) * factor, cv + (win.b - cv) * factor,
                               cv + (win.t - cv) * factor};
        return cam;
    }
    cam.eye = cam.look_at + (cam.eye - cam.look_at) * factor;
    return cam;
}

} // namespace viewer
