// aov.hpp - what a render computes at each sample: the shaded color, or a
// debug image of the hits (an "arbitrary output variable": depth, normal,
// position, or the camera ray's direction). How each is stored:
// encoded_output.hpp (output_encoding).
//
//     const rt::aov_kind kind = rt::aov_from_name("depth").value();  // --aov depth
#pragma once

#include <optional>
#include <string>

#include "../core/enum_names.hpp"

namespace rt {

/// What each sample computes: the shaded color (shaded) or a debug image (an
/// "arbitrary output variable"): the hit's distance, its normal, its position,
/// or the camera ray's direction.
enum class aov_kind { shaded, depth, normal, position, rays };

/// The names of the debug images; "shaded" is not a debug image.
inline constexpr detail::enum_name<aov_kind> aov_names[] = {{aov_kind::shaded, "shaded"},
                                                            {aov_kind::depth, "depth"},
                                                            {aov_kind::normal, "normal"},
                                                            {aov_kind::position, "position"},
                                                            {aov_kind::rays, "rays"}};

/// The debug image a name means ("depth", "normal", "position", "rays"), or nothing.
inline std::optional<aov_kind> aov_from_name(const std::string& name)
{
    const std::optional<aov_kind> kind = detail::value_named(aov_names, name);
    return kind == aov_kind::shaded ? std::nullopt : kind;
}

/// "shaded" for aov_kind::shaded, otherwise the name aov_from_name reads.
inline const char* name_of(aov_kind kind) { return detail::name_in(aov_names, kind); }

} // namespace rt
