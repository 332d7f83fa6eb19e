// rt/encoded_output.hpp - a forwarder for one release (0.2): the header moved to output/.
// Include <rt/output/encoded_output.hpp> instead. Nothing else is here, and it defines no macro.
#pragma once
#if defined(_MSC_VER) && !defined(__clang__)
#pragma message("<rt/encoded_output.hpp> is deprecated: include <rt/output/encoded_output.hpp> (CHANGELOG.md, 0.2.0)")
#else
#warning "<rt/encoded_output.hpp> is deprecated: include <rt/output/encoded_output.hpp> (CHANGELOG.md, 0.2.0)"
#endif
#include <rt/output/encoded_output.hpp>
