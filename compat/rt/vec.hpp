// rt/vec.hpp - a forwarder for one release (0.2): the header moved to core/.
// Include <rt/core/vec.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/vec.hpp> is deprecated: include <rt/core/vec.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/vec.hpp> is deprecated: include <rt/core/vec.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/core/vec.hpp>
