// rt/progress.hpp - a forwarder for one release (0.2): the header moved to rendering/.
// Include <rt/rendering/progress.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/progress.hpp> is deprecated: include <rt/rendering/progress.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/progress.hpp> is deprecated: include <rt/rendering/progress.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/rendering/progress.hpp>
