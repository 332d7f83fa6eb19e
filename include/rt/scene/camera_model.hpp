// camera_model.hpp - the camera as a scene file declares it (stage 01 reads
// it, stage 02 turns it into rays): projection, eye, look-at, up, field of view
// or window, focal distance. Only the data: the frame and the rays are
// camera.hpp's (stage 02), so the scene and its loader include no exercise.
#pragma once

#include <optional>
#include <string>

#include "../core/enum_names.hpp"
#include "../core/vec.hpp"

namespace rt {

enum class projection { perspective, orthographic };

/// The words a scene file, a --camera option and the programs name them by.
inline constexpr detail::enum_name<projection> projection_names[] = {{projection::perspective, "perspective"},
                                                                     {projection::orthographic, "orthographic"}};

inline std::optional<projection> projection_from_name(const std::string& name)
{
    return detail::value_named(projection_names, name);
}

inline const char* name_of(projection kind) { return detail::name_in(projection_names, kind); }

/// The image-plane window: the u range [l, r] and the v range [b, t].
struct window {
    real l = -1, r = 1, b = -1, t = 1;
};

/// The camera as a scene file declares it. Either a vertical field of view or
/// an explicit window; when neither is given, a perspective camera uses a
/// 45 degree field of view and an orthographic one the window [-1, 1] in v,
/// widened to the image's aspect ratio.
struct camera {
    projection kind = projection::perspective;
    vec3 eye{0, 0, 1};      ///< e
    vec3 look_at{0, 0, 0};  ///< the point the camera looks at
    vec3 up{0, 1, 0};       ///< up vector; need not be orthogonal to the view direction
    std::optional<real> fov_degrees;  ///< vertical field of view (perspective only)
    std::optional<window> plane;      ///< explicit window l, r, b, t
    real focal_distance = 1;          ///< d, the distance from e to the image plane
};

/// A thin lens in front of a perspective camera (stage 10, the scene file's
/// `lens` statement; FCG 4th ed., sec. 13.4.3): rays leave a disk of radius
/// `aperture` around e and meet on the plane in focus, at distance `focus`
/// from e along the view direction. Aperture 0 is the pinhole of stage 02.
struct lens_model {
    real aperture = 0;  ///< the lens radius
    real focus = 1;     ///< the distance from e to the plane in focus
};

} // namespace rt
