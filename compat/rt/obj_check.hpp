// rt/obj_check.hpp - a forwarder for one release (0.2): the header moved to input/.
// Include <rt/input/obj_check.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/obj_check.hpp> is deprecated: include <rt/input/obj_check.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/obj_check.hpp> is deprecated: include <rt/input/obj_check.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/input/obj_check.hpp>
