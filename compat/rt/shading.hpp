// rt/shading.hpp - a forwarder for one release (0.2): the header moved to shading/.
// Include <rt/shading/shading.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/shading.hpp> is deprecated: include <rt/shading/shading.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/shading.hpp> is deprecated: include <rt/shading/shading.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/shading/shading.hpp>
