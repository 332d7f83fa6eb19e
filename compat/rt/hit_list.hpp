// rt/hit_list.hpp - a forwarder for one release (0.2): the header moved to intersection/.
// Include <rt/intersection/hit_list.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/hit_list.hpp> is deprecated: include <rt/intersection/hit_list.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/hit_list.hpp> is deprecated: include <rt/intersection/hit_list.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/intersection/hit_list.hpp>
