// rt/spawn.hpp - a forwarder for one release (0.2): the header moved to intersection/.
// Include <rt/intersection/spawn.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/spawn.hpp> is deprecated: include <rt/intersection/spawn.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/spawn.hpp> is deprecated: include <rt/intersection/spawn.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/intersection/spawn.hpp>
