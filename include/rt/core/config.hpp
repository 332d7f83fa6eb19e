// config.hpp - the scalar type of the whole library.
//
// rt::real is float by default: it is fast, and the robust methods of the later
// stages keep float results accurate. Configure with -DRT_USE_DOUBLE=ON and the
// CMake target defines RT_USE_DOUBLE=1 for every translation unit that links
// rt::rt, so a program and its libraries always agree on the type.
#pragma once

namespace rt {

#if defined(RT_USE_DOUBLE) && RT_USE_DOUBLE
using real = double;
#else
using real = float;
#endif

} // namespace rt
