// bvh/abi_begin.hpp - decides which fast path this translation unit compiles
// (RT_BVH_SSE, RT_BVH_AVX, RT_BVH_AVX2, from the compiler's target) and names
// it: RT_BVH_ABI, the inline namespace that holds the width-dependent types
// and functions (bvh_w8 with AVX2's 8-wide nodes, else bvh_w4). Without it a
// program whose units are compiled for different targets (one with -mavx2)
// would have two layouts of rt::bvh_node under one name, and the linker,
// keeping one copy of each inline function, could pair one unit's build with
// the other's traversal; with it each unit has its own types, and passing one
// unit's accelerator to the other is a link error, not a wrong answer
// (tests/library_mixed_targets.cpp). Includes no intrinsics: a header that
// only names the types (stages/common/support.hpp) stays light. bvh/simd_end.hpp
// takes the macros away. (No #pragma once: each section opens anew.)
//
//     #include "abi_begin.hpp"
//     namespace rt { inline namespace RT_BVH_ABI { class accelerator; } }
//     #include "simd_end.hpp"

#include "../config.hpp" // RT_USE_DOUBLE

// RT_BVH_SSE: SSE2 is there (every x86-64 compiler) and rt::real is float.
#if !defined(RT_BVH_SSE)
#if (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2)) && \
    !(defined(RT_USE_DOUBLE) && RT_USE_DOUBLE)
#define RT_BVH_SSE 1
#else
#define RT_BVH_SSE 0
#endif
#endif

// RT_BVH_AVX: AVX is there too (-mavx, -march=native on a recent x86-64): the
// leaf test then converts four lanes to double at once.
#if !defined(RT_BVH_AVX)
#if RT_BVH_SSE && defined(__AVX__)
#define RT_BVH_AVX 1
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

// RT_BVH_ABI: the inline namespace of this width (see the top of this file).
#if !defined(RT_BVH_ABI)
#if RT_BVH_AVX2
#define RT_BVH_ABI bvh_w8
#else
#define RT_BVH_ABI bvh_w4
#endif
#endif
