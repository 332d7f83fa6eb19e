// rt/adaptive.hpp - a forwarder for one release (0.2): the header moved to path_tracing/.
// Include <rt/path_tracing/adaptive.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/adaptive.hpp> is deprecated: include <rt/path_tracing/adaptive.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/adaptive.hpp> is deprecated: include <rt/path_tracing/adaptive.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/path_tracing/adaptive.hpp>
