// rt/ray_image.hpp - a forwarder for one release (0.2): the header moved to camera/.
// Include <rt/camera/ray_image.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/ray_image.hpp> is deprecated: include <rt/camera/ray_image.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/ray_image.hpp> is deprecated: include <rt/camera/ray_image.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/camera/ray_image.hpp>
