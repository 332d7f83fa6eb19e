// rt/bvh.hpp - a forwarder for one release (0.2): the header moved to bvh/.
// Include <rt/bvh/bvh.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/bvh.hpp> is deprecated: include <rt/bvh/bvh.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/bvh.hpp> is deprecated: include <rt/bvh/bvh.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/bvh/bvh.hpp>
