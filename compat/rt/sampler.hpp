// rt/sampler.hpp - a forwarder for one release (0.2): the header moved to rendering/.
// Include <rt/rendering/sampler.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/sampler.hpp> is deprecated: include <rt/rendering/sampler.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/sampler.hpp> is deprecated: include <rt/rendering/sampler.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/rendering/sampler.hpp>
