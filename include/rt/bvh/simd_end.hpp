// bvh/simd_end.hpp - closes the SIMD section simd_begin.hpp (or abi_begin.hpp) opened: the
// macros it defined go, so no fast-path macro reaches an includer.
// (No #pragma once: each section closes anew.)

#undef RT_BVH_SSE
#undef RT_BVH_AVX
#undef RT_BVH_AVX2
#undef RT_BVH_INLINE
#undef RT_BVH_ABI
