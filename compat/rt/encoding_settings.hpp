// rt/encoding_settings.hpp - a forwarder for one release (0.2): the header moved to output/.
// Include <rt/output/encoding_settings.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/encoding_settings.hpp> is deprecated: include <rt/output/encoding_settings.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/encoding_settings.hpp> is deprecated: include <rt/output/encoding_settings.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/output/encoding_settings.hpp>
