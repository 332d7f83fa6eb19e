// rt/shape_statements.hpp - a forwarder for one release (0.2): the header moved to input/.
// Include <rt/input/shape_statements.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/shape_statements.hpp> is deprecated: include <rt/input/shape_statements.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/shape_statements.hpp> is deprecated: include <rt/input/shape_statements.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/input/shape_statements.hpp>
