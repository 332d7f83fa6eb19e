// rt/camera_text.hpp - a forwarder for one release (0.2): the header moved to camera/.
// Include <rt/camera/camera_text.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/camera_text.hpp> is deprecated: include <rt/camera/camera_text.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/camera_text.hpp> is deprecated: include <rt/camera/camera_text.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/camera/camera_text.hpp>
