// rt/area_light.hpp - a forwarder for one release (0.2): the header moved to scene/.
// Include <rt/scene/area_light.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/area_light.hpp> is deprecated: include <rt/scene/area_light.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/area_light.hpp> is deprecated: include <rt/scene/area_light.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/scene/area_light.hpp>
