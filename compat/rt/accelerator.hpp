// rt/accelerator.hpp - a forwarder for one release (0.2): the header moved to bvh/.
// Include <rt/bvh/accelerator.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/accelerator.hpp> is deprecated: include <rt/bvh/accelerator.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/accelerator.hpp> is deprecated: include <rt/bvh/accelerator.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/bvh/accelerator.hpp>
