// bvh/accelerator_fwd.hpp - rt::accelerator declared, not defined, as <iosfwd>
// declares the streams: for a header that only names it (a pointer, a
// reference, a function that takes one) and should stay light.
//
//     #include <rt/bvh/accelerator_fwd.hpp>
//     void trace(const rt::accelerator& world);   // its definition includes accelerator.hpp
//
// rt::accelerator lives in the inline namespace of this unit's fast path
// (bvh/abi_begin.hpp says why), so a plain `namespace rt { class accelerator; }`
// would declare another class; this header names the right one, and
// includes no intrinsics.
#pragma once

#include "abi_begin.hpp"
namespace rt {
inline namespace RT_BVH_ACCELERATOR_ABI {
class accelerator;
}
} // namespace rt
#include "simd_end.hpp"
