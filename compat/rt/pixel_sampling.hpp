// rt/pixel_sampling.hpp - a forwarder for one release (0.2): the header moved to camera/.
// Include <rt/camera/pixel_sampling.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/pixel_sampling.hpp> is deprecated: include <rt/camera/pixel_sampling.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/pixel_sampling.hpp> is deprecated: include <rt/camera/pixel_sampling.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/camera/pixel_sampling.hpp>
