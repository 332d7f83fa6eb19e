// rt/raytracer.hpp - a forwarder for one release (0.2): the header moved to shading/.
// Include <rt/shading/raytracer.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/raytracer.hpp> is deprecated: include <rt/shading/raytracer.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/raytracer.hpp> is deprecated: include <rt/shading/raytracer.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/shading/raytracer.hpp>
