// rt/intersect.hpp - a forwarder for one release (0.2): removed in 0.1, it re-included two headers.
// Include <rt/bvh/accelerator.hpp> and <rt/intersection/hit_list.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/intersect.hpp> is deprecated: include <rt/bvh/accelerator.hpp> and <rt/intersection/hit_list.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/intersect.hpp> is deprecated: include <rt/bvh/accelerator.hpp> and <rt/intersection/hit_list.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/bvh/accelerator.hpp>
#include <rt/intersection/hit_list.hpp>
