// aov.hpp - what a render computes at each sample: the shaded colour, or a
// debug image of the hits (an "arbitrary output variable": depth, normal,
// position, or the camera ray's direction). How each is stored:
// encoded_output.hpp (output_encoding).
//
//     const rt::aov_kind kind = rt::aov_from_name("depth").value();  // --aov depth
#pragma once

#include <optional>
#include <string>


namespace rt {

/// What each sample computes: the shaded colour (none) or a debug image (an
/// "arbitrary output variable"): the hit's distance, its normal, its position,
/// or the camera ray's direction.
enum class aov_kind { none, depth, normal, position, rays };

inline std::optional<aov_kind> aov_from_name(const std::string& name)
{
    if (name == "depth")
        return aov_kind::depth;
    if (name == "normal")
        return aov_kind::normal;
    if (name == "position")
        return aov_kind::position;
    if (name == "rays")
        return aov_kind::rays;
    return std::nullopt;
}

/// "shaded" for aov_kind::none, otherwise the name aov_from_name reads.
inline const char* name_of(aov_kind kind)
{
    switch (kind) {
    case aov_kind::depth: return "depth";
    case aov_kind::normal: return "normal";
    case aov_kind::position: return "position";
    case aov_kind::rays: return "rays";
    case aov_kind::none: break;
    }
    return "shaded";
}

} // namespace rt
