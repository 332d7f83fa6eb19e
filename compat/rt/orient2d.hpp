// rt/orient2d.hpp - a forwarder for one release (0.2): the header moved to input/.
// Include <rt/input/orient2d.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/orient2d.hpp> is deprecated: include <rt/input/orient2d.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/orient2d.hpp> is deprecated: include <rt/input/orient2d.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/input/orient2d.hpp>
