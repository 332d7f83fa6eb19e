// bvh/simd_begin.hpp - opens the SIMD section of a fast-path header: defines
// RT_BVH_SSE, RT_BVH_AVX, RT_BVH_AVX2 and RT_BVH_ABI (abi_begin.hpp), includes
// the intrinsics they allow, and defines RT_BVH_INLINE. Every header that
// includes it includes simd_end.hpp after its last line of code, so the five
// macros never leave the fast path (no #pragma once: each section opens anew).
//
//     #include "simd_begin.hpp"
//     #if RT_BVH_SSE
//     ... __m128 code ...
//     #endif
//     #include "simd_end.hpp"

#include "abi_begin.hpp" // RT_BVH_SSE, RT_BVH_AVX, RT_BVH_AVX2, RT_BVH_ABI

#if RT_BVH_SSE
#include <emmintrin.h>
#endif
#if RT_BVH_AVX
#include <immintrin.h>
#endif

// RT_BVH_INLINE: a per-ray kernel the compiler must inline into the traversal
// loop (g++ kept the leaf test a call: its ray's rows and registers were then
// reloaded for every block; docs/performance.md, experiment 6).
#if !defined(RT_BVH_INLINE)
#if defined(__GNUC__) || defined(__clang__)
#define RT_BVH_INLINE inline __attribute__((always_inline))
#elif defined(_MSC_VER)
#define RT_BVH_INLINE __forceinline
#else
#define RT_BVH_INLINE inline
#endif
#endif
