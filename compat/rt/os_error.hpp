// rt/os_error.hpp - a forwarder for one release (0.2): the header moved to system/.
// Include <rt/system/os_error.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/os_error.hpp> is deprecated: include <rt/system/os_error.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/os_error.hpp> is deprecated: include <rt/system/os_error.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/system/os_error.hpp>
