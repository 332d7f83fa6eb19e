// rt/mis.hpp - a forwarder for one release (0.2): the header moved to path_tracing/.
// Include <rt/path_tracing/mis.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/mis.hpp> is deprecated: include <rt/path_tracing/mis.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/mis.hpp> is deprecated: include <rt/path_tracing/mis.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/path_tracing/mis.hpp>
