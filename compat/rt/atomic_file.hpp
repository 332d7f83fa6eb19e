// rt/atomic_file.hpp - a forwarder for one release (0.2): the header moved to system/.
// Include <rt/system/atomic_file.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/atomic_file.hpp> is deprecated: include <rt/system/atomic_file.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/atomic_file.hpp> is deprecated: include <rt/system/atomic_file.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/system/atomic_file.hpp>
