// rt/render_setup.hpp - a forwarder for one release (0.2): the header moved to rendering/.
// Include <rt/rendering/render_setup.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/render_setup.hpp> is deprecated: include <rt/rendering/render_setup.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/render_setup.hpp> is deprecated: include <rt/rendering/render_setup.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/rendering/render_setup.hpp>
