// rt/path_text.hpp - a forwarder for one release (0.2): the header moved to system/.
// Include <rt/system/path_text.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/path_text.hpp> is deprecated: include <rt/system/path_text.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/path_text.hpp> is deprecated: include <rt/system/path_text.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/system/path_text.hpp>
