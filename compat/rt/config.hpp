// rt/config.hpp - a forwarder for one release (0.2): the header moved to core/.
// Include <rt/core/config.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/config.hpp> is deprecated: include <rt/core/config.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/config.hpp> is deprecated: include <rt/core/config.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/core/config.hpp>
