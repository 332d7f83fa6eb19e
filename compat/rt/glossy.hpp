// rt/glossy.hpp - a forwarder for one release (0.2): the header moved to shading/.
// Include <rt/shading/glossy.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/glossy.hpp> is deprecated: include <rt/shading/glossy.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/glossy.hpp> is deprecated: include <rt/shading/glossy.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/shading/glossy.hpp>
