// rt/triangle_shape.hpp - a forwarder for one release (0.2): the header moved to scene/.
// Include <rt/scene/triangle_shape.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/triangle_shape.hpp> is deprecated: include <rt/scene/triangle_shape.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/triangle_shape.hpp> is deprecated: include <rt/scene/triangle_shape.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/scene/triangle_shape.hpp>
