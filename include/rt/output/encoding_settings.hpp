// encoding_settings.hpp - the settings of stage 08's color pipeline: the
// exposure, which tone map, which transfer curve (sRGB or a plain gamma).
//
// Only the names and the settings, none of the curves (tonemap.hpp,
// transfer.hpp) and none of the pipeline (encoding.hpp): a program that reads
// --tonemap or --gamma from its command line includes this header, so an edit
// to a stage-08 exercise does not recompile it.
//
//     rt::encoding enc;                         // clamp, sRGB, exposure 0
//     enc.tonemap = *rt::tonemap_from_name("aces");
#pragma once

#include <optional>
#include <string>

#include "../core/enum_names.hpp"

namespace rt {

/// The tone maps the renderer offers (names as on the command line: clamp, reinhard, aces).
enum class tonemap_kind { clamp, reinhard, aces };

/// The names of the tone maps; the first is the default.
inline constexpr detail::enum_name<tonemap_kind> tonemap_names[] = {
    {tonemap_kind::clamp, "clamp"}, {tonemap_kind::reinhard, "reinhard"}, {tonemap_kind::aces, "aces"}};

/// The tone map a name means ("clamp", "reinhard", "aces"), or nothing.
inline std::optional<tonemap_kind> tonemap_from_name(const std::string& name)
{
    return detail::value_named(tonemap_names, name);
}

inline const char* name_of(tonemap_kind kind) { return detail::name_in(tonemap_names, kind); }

/// The curve from a tone-mapped value in [0, 1] to the value stored.
enum class transfer_kind { srgb, gamma };

/// How linear colors become bytes: the settings of the whole pipeline.
struct encoding {
    float exposure = 0.0f;                       ///< stops: colors are scaled by 2^exposure
    tonemap_kind tonemap = tonemap_kind::clamp;  ///< the curve from [0, inf) to [0, 1]
    transfer_kind transfer = transfer_kind::srgb;
    float gamma = 2.2f;                          ///< used when transfer == gamma
};

} // namespace rt
