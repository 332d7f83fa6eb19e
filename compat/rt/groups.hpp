// rt/groups.hpp - a forwarder for one release (0.2): the header moved to intersection/.
// Include <rt/intersection/groups.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/groups.hpp> is deprecated: include <rt/intersection/groups.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/groups.hpp> is deprecated: include <rt/intersection/groups.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/intersection/groups.hpp>
