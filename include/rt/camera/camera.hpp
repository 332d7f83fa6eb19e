// camera.hpp - the camera, its frame u, v, w, and one ray per pixel (stage 02).
//
// Fundamentals of Computer Graphics (Shirley, Marschner), 4th ed., sec. 4.3:
//   frame (sec. 4.3, 2.4.7): w = -(look_at - e)/|look_at - e|, u = (up x w)/|up x w|, v = w x u
//   pixel to image plane (eq. 4.1):  u = l + (r - l)(i + 0.5)/nx,  v = b + (t - b)(j + 0.5)/ny
//   orthographic (sec. 4.3.1):       origin e + u u + v v,      direction -w
//   perspective  (sec. 4.3.2):       origin e,                  direction -d w + u u + v v
// The image row j counts from the bottom, as in the book; rt::image stores the
// top row first, so pixel (i, j) lives at image row ny - 1 - j.
#pragma once

#include <cmath>
#include <optional>
#include <string>

#include "../scene/camera_model.hpp"
#include "../core/error.hpp"
#include "../core/ray.hpp"
#include "../core/vec.hpp"

namespace rt {

/// A right-handed orthonormal basis: u right, v up, w backwards (away from the view).
struct frame {
    vec3 u{1, 0, 0}, v{0, 1, 0}, w{0, 0, 1};
};

/// The camera frame from the eye e, the look-at point and the up vector.
/// Precondition: e != look_at and up is not parallel to the view direction
/// (the scene loader rejects both).
inline frame make_frame(const vec3& e, const vec3& look_at, const vec3& up)
{
    // RT_EXERCISE_BEGIN(stage02: camera frame)
    frame f;
    f.w = glm::normalize(e - look_at);
    f.u = glm::normalize(glm::cross(up, f.w));
    f.v = glm::cross(f.w, f.u);
    return f;
    // RT_EXERCISE_END
}

/// The window of a vertical field of view at focal distance d, keeping the
/// image's aspect ratio nx/ny (square pixels): t = d tan(fov/2), r = t nx/ny.
inline window window_from_fov(real fov_degrees, real d, int nx, int ny)
{
    // RT_EXERCISE_BEGIN(stage02: field of view to window)
    const real pi = real(3.14159265358979323846);
    const real t = d * std::tan(fov_degrees * pi / real(360));
    const real r = t * real(nx) / real(ny);
    return window{-r, r, -t, t};
    // RT_EXERCISE_END
}

/// The window the camera uses for an nx by ny image (see struct camera).
inline window effective_window(const camera& cam, int nx, int ny)
{
    if (cam.plane)
        return *cam.plane;
    if (cam.kind == projection::perspective)
        return window_from_fov(cam.fov_degrees.value_or(real(45)), cam.focal_distance, nx, ny);
    const real aspect = real(nx) / real(ny);
    return window{-aspect, aspect, -1, 1};
}

/// Everything ray generation needs, computed once per image rather than per ray.
struct ray_generator {
    projection kind = projection::perspective;
    vec3 e{0};
    frame basis;
    window plane;
    real d = 1;
    int nx = 1, ny = 1;
};

namespace detail {

inline bool finite(const vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

} // namespace detail

/// The ray generator of `cam` for an nx x ny image. A camera from a scene file
/// was checked by the loader (stage 01); one built in code is checked here, on
/// what it gives: an rt::error, never rays of NaN, when it has no frame (eye
/// at look_at, up parallel to the view direction), an empty or infinite
/// window (a field of view outside (0, 180) degrees) or a focal distance that
/// is not a positive number.
inline ray_generator make_ray_generator(const camera& cam, int nx, int ny)
{
    if (nx < 1 || ny < 1)
        throw error("camera: expected an image of at least 1 x 1 pixels, found " + std::to_string(nx) + " x " +
                    std::to_string(ny));
    if (!detail::finite(cam.eye) || !detail::finite(cam.look_at) || !detail::finite(cam.up))
        throw error("camera: expected finite eye, look_at and up, found a NaN or an infinity");
    if (!(cam.focal_distance > 0 && std::isfinite(cam.focal_distance)))
        throw error("camera: expected a focal distance > 0, found " + detail::short_number(double(cam.focal_distance)));
    ray_generator gen;
    gen.kind = cam.kind;
    gen.e = cam.eye;
    gen.basis = make_frame(cam.eye, cam.look_at, cam.up);
    if (!detail::finite(gen.basis.u) || !detail::finite(gen.basis.v) || !detail::finite(gen.basis.w))
        throw error("camera: expected a camera frame, found none (NaN); eye must differ from look_at and up must "
                    "not be parallel to look_at - eye");
    // checked here, not left to the window: tan(90 degrees) is about -2e7 in
    // float (an empty window) but 1.6e16 in double (a huge one, accepted)
    if (!cam.plane && cam.kind == projection::perspective && cam.fov_degrees &&
        !(*cam.fov_degrees > 0 && *cam.fov_degrees < 180))
        throw error("camera: expected a field of view in (0, 180) degrees, found " +
                    detail::short_number(double(*cam.fov_degrees)));
    gen.plane = effective_window(cam, nx, ny);
    const window& p = gen.plane;
    if (!(p.l < p.r && p.b < p.t && std::isfinite(p.r - p.l) && std::isfinite(p.t - p.b)))
        throw error("camera: expected a window with l < r and b < t, all finite, found " +
                    detail::short_number(double(p.l)) + " " + detail::short_number(double(p.r)) + " " +
                    detail::short_number(double(p.b)) + " " + detail::short_number(double(p.t)) +
                    "; a field of view must lie in (0, 180) degrees");
    gen.d = cam.focal_distance;
    gen.nx = nx;
    gen.ny = ny;
    return gen;
}

/// The ray through the image position (x, y), measured in pixels from the
/// bottom-left corner of the image: pixel (i, j)'s centre is (i + 0.5, j + 0.5),
/// so the book's eq. 4.1 is u = l + (r - l) x / nx, v = b + (t - b) y / ny.
/// Samplers pass other positions inside the pixel.
inline ray generate_ray(const ray_generator& gen, real x, real y)
{
    // RT_EXERCISE_BEGIN(stage02: generate a ray)
    const window& win = gen.plane;
    const real u = win.l + (win.r - win.l) * x / real(gen.nx);
    const real v = win.b + (win.t - win.b) * y / real(gen.ny);
    const vec3 offset = u * gen.basis.u + v * gen.basis.v;
    if (gen.kind == projection::orthographic)
        return ray{gen.e + offset, -gen.basis.w};
    return ray{gen.e, offset - gen.d * gen.basis.w};
    // RT_EXERCISE_END
}

/// The ray through the centre of pixel (i, j), j counted from the bottom row.
inline ray pixel_ray(const ray_generator& gen, int i, int j)
{
    return generate_ray(gen, real(i) + real(0.5), real(j) + real(0.5));
}

} // namespace rt
