// camera_text.hpp - a camera written as the arguments of a scene file's
// `camera` statement, every number so that it reads back exactly (the inverse
// of parse_camera_statement, camera_statement.hpp).
//
//     std::cout << "camera " << rt::camera_statement(s.cam) << '\n';
#pragma once

#include <charconv>
#include <string>
#include <system_error>

#include "../scene/camera_model.hpp"
#include "../core/config.hpp"
#include "../core/decimal_text.hpp"
#include "../core/vec.hpp"

namespace rt {

/// `value` as the shortest text that the scene loader and the command-line
/// options (which read it as decimal_text.hpp does, to the rt::real nearest
/// the text) turn back into exactly `value`; the 17 digits of the double
/// otherwise, which always come back exactly.
inline std::string exact_number_text(real value)
{
    char buffer[64];
    auto read_back = [](const char* first, const char* last) {
        double parsed = 0;
        detail::read_decimal<real>(first, last, parsed);
        return real(detail::rounded_to<real>(parsed));
    };
    const std::to_chars_result shortest = std::to_chars(buffer, buffer + sizeof buffer, value);
    if (shortest.ec == std::errc() && read_back(buffer, shortest.ptr) == value)
        return std::string(buffer, shortest.ptr);
    const std::to_chars_result full =
        std::to_chars(buffer, buffer + sizeof buffer, double(value), std::chars_format::general, 17);
    return std::string(buffer, full.ptr);
}

namespace detail {

inline std::string exact_vector_text(const vec3& v)
{
    return exact_number_text(v.x) + ' ' + exact_number_text(v.y) + ' ' + exact_number_text(v.z);
}

} // namespace detail

/// The camera as the arguments of a scene file's `camera` statement
/// (docs/scene-format.md), every number written so that it reads back exactly:
/// "perspective eye 0 1.6 6 look_at 0 0.7 0 up 0 1 0 fov 40 focal 1".
inline std::string camera_statement(const camera& cam)
{
    std::string text = name_of(cam.kind);
    text += " eye " + detail::exact_vector_text(cam.eye);
    text += " look_at " + detail::exact_vector_text(cam.look_at);
    text += " up " + detail::exact_vector_text(cam.up);
    if (cam.plane)
        text += " window " + exact_number_text(cam.plane->l) + ' ' + exact_number_text(cam.plane->r) +
                ' ' + exact_number_text(cam.plane->b) + ' ' + exact_number_text(cam.plane->t);
    else if (cam.fov_degrees)
        text += " fov " + exact_number_text(*cam.fov_degrees);
    text += " focal " + exact_number_text(cam.focal_distance);
    return text;
}

} // namespace rt
