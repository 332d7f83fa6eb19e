// rt/tonemap.hpp - a forwarder for one release (0.2): the header moved to output/.
// Include <rt/output/tonemap.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/tonemap.hpp> is deprecated: include <rt/output/tonemap.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/tonemap.hpp> is deprecated: include <rt/output/tonemap.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/output/tonemap.hpp>
