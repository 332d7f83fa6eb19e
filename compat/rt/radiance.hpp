// rt/radiance.hpp - a forwarder for one release (0.2): the header moved to rendering/.
// Include <rt/rendering/radiance.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/radiance.hpp> is deprecated: include <rt/rendering/radiance.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/radiance.hpp> is deprecated: include <rt/rendering/radiance.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/rendering/radiance.hpp>
