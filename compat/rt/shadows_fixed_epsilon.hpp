// rt/shadows_fixed_epsilon.hpp - a forwarder for one release (0.2): the header moved to shading/.
// Include <rt/shading/shadows_fixed_epsilon.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/shadows_fixed_epsilon.hpp> is deprecated: include <rt/shading/shadows_fixed_epsilon.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/shadows_fixed_epsilon.hpp> is deprecated: include <rt/shading/shadows_fixed_epsilon.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/shading/shadows_fixed_epsilon.hpp>
