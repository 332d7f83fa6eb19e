// bvh/simd_begin.hpp - opens the SIMD section of a fast-path header: defines
// RT_BVH_SSE, RT_BVH_AVX and RT_BVH_AVX2, includes the intrinsics they allow,
// and defines RT_BVH_INLINE. Every header that includes it includes simd_end.hpp after
// its last line of code, so the four macros never leave the fast path (no
// #pragma once: each section opens anew).
//
//     #include "simd_begin.hpp"
//     #if RT_BVH_SSE
//     ... __m128 code ...
//     #endif
//     #include "simd_end.hpp"

#include "../config.hpp" // RT_USE_DOUBLE

// RT_BVH_SSE: SSE2 is there (every x86-64 compiler) and rt::real is float.
#if !defined(RT_BVH_SSE)
#if (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)) && \
    !(defined(RT_USE_DOUBLE) && RT_USE_DOUBLE)
#define RT_BVH_SSE 1
#include <emmintrin.h>
#else
#define RT_BVH_SSE 0
#endif
#endif

// RT_BVH_AVX: AVX is there too (-mavx, -march=native on a recent x86-64): the
// leaf test then converts four lanes to double at once.
#if !defined(RT_BVH_AVX)
#if RT_BVH_SSE && defined(__AVX__)
#define RT_BVH_AVX 1
#include <immintrin.h>
#else
#define RT_BVH_AVX 0
#endif
#endif

// RT_BVH_AVX2: AVX2 is there too (-mavx2, -march=native on an x86-64 from
// 2013 on): nodes are 8-wide (layout.hpp), the children they meet ordered
// with 256-bit integer operations (descend.hpp).
#if !defined(RT_BVH_AVX2)
#if RT_BVH_AVX && defined(__AVX2__)
#define RT_BVH_AVX2 1
#else
#define RT_BVH_AVX2 0
#endif
#endif

// RT_BVH_INLINE: a per-ray kernel the compiler must inline into the traversal
// loop (g++ kept the leaf test a call: its ray's rows and registers were then
// reloaded for every block; docs/performance.md, experiment 6).
#if !defined(RT_BVH_INLINE)
#if defined(__GNUC__) || defined(__clang__)
#define RT_BVH_INLINE inline __attribute__((always_inline))
#else
#define RT_BVH_INLINE inline
#endif
#endif
