// bvh/simd_end.hpp - closes the SIMD section simd_begin.hpp (or abi_begin.hpp) opened: the
// macros it defined go, so no fast-path macro reaches an includer; a macro
// the user set (RT_BVH_SSE, RT_BVH_AVX, RT_BVH_AVX2) stays for the next section.
// (No #pragma once: each section closes anew.)

#if defined(RT_BVH_OWNS_SSE)
#undef RT_BVH_SSE
#undef RT_BVH_OWNS_SSE
#endif
#if defined(RT_BVH_OWNS_AVX)
#undef RT_BVH_AVX
#undef RT_BVH_OWNS_AVX
#endif
#if defined(RT_BVH_OWNS_AVX2)
#undef RT_BVH_AVX2
#undef RT_BVH_OWNS_AVX2
#endif
#undef RT_BVH_INLINE
#undef RT_BVH_ABI
#undef RT_BVH_ABI_INLINE
#undef RT_BVH_DISPATCH
#undef RT_BVH_DISPATCH_AVX512
#undef RT_BVH_AVX512
#undef RT_BVH_ACCELERATOR_ABI
