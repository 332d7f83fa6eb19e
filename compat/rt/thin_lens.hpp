// rt/thin_lens.hpp - a forwarder for one release (0.2): the header moved to camera/.
// Include <rt/camera/thin_lens.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/thin_lens.hpp> is deprecated: include <rt/camera/thin_lens.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/thin_lens.hpp> is deprecated: include <rt/camera/thin_lens.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/camera/thin_lens.hpp>
