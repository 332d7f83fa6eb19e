// rt/scene_statement.hpp - a forwarder for one release (0.2): the header moved to input/.
// Include <rt/input/scene_statement.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/scene_statement.hpp> is deprecated: include <rt/input/scene_statement.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/scene_statement.hpp> is deprecated: include <rt/input/scene_statement.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/input/scene_statement.hpp>
