// bvh/abi_begin.hpp - decides which fast path this section of a translation
// unit compiles (RT_BVH_SSE, RT_BVH_AVX, RT_BVH_AVX2, from the compiler's
// target) and names it: RT_BVH_ABI, the namespace that holds the
// width-dependent types and functions (bvh_w8 with AVX2's 8-wide nodes, else
// bvh_w4). Without it a program whose units are compiled for different
// targets (one with -mavx2) would have two layouts of rt::detail::bvh_node under one
// name, and the linker, keeping one copy of each inline function, could pair
// one unit's build with the other's traversal; with it each unit has its own
// types, and passing one unit's accelerator to the other is a link error, not
// a wrong answer (tests/library_mixed_targets.cpp). Includes no intrinsics: a
// header that only names the types (accelerator_fwd.hpp) stays light.
// bvh/simd_end.hpp takes the macros away. (No #pragma once: each section opens anew.)
//
//     #include "abi_begin.hpp"
//     namespace rt { inline namespace RT_BVH_ACCELERATOR_ABI { class accelerator; } }
//     #include "simd_end.hpp"
//
// Run-time dispatch (bvh/dispatch.hpp): where the target lacks AVX2 but the
// compiler can compile single functions for it (g++ and clang++ on x86-64,
// MSVC there too), RT_BVH_DISPATCH is 1: the unit compiles the 4-wide SSE path
// as its target allows, then the 8-wide AVX2 path a second time under
// target("avx2,bmi,bmi2,popcnt") in the namespace rt::bvh_w8 (not inline: rt::bvh stays the
// 4-wide tree), with g++ and clang++ a third time with AVX-512 added in
// rt::bvh_w8_avx512 (RT_BVH_DISPATCH_AVX512), and rt::accelerator, in the
// namespace bvh_dispatch (RT_BVH_ACCELERATOR_ABI), walks the widest the CPU runs. A unit whose target has
// AVX2 (-mavx2, -march=native on an AVX2 machine) skips the dispatch, and so
// does one that sets RT_BVH_AVX2 itself: -DRT_BVH_AVX2=0 forces the 4-wide
// path; -DRT_BVH_AVX2=1 the 8-wide one, which needs an AVX2 target.
//
// The macros a user may set (RT_BVH_SSE, RT_BVH_AVX, RT_BVH_AVX2) are kept to
// the end of the unit: simd_end.hpp removes only those this file defined
// (RT_BVH_OWNS_*), so every section sees the user's choice.

#include "../core/config.hpp" // RT_USE_DOUBLE

#if defined(RT_BVH_AVX2_SECTION)
// bvh/dispatch.hpp's second section: the 8-wide path, compiled under
// target("avx2,bmi,bmi2,popcnt") in a unit whose target lacks AVX2; or its
// third (RT_BVH_AVX512_SECTION too): the same code under AVX-512's target
// as well, in rt::bvh_w8_avx512
#define RT_BVH_SSE 1
#define RT_BVH_AVX 1
#define RT_BVH_AVX2 1
#define RT_BVH_OWNS_SSE
#define RT_BVH_OWNS_AVX
#define RT_BVH_OWNS_AVX2
#if defined(RT_BVH_AVX512_SECTION)
#define RT_BVH_AVX512 1
#define RT_BVH_ABI bvh_w8_avx512
#else
#define RT_BVH_AVX512 0
#define RT_BVH_ABI bvh_w8
#endif
#define RT_BVH_ABI_INLINE
#define RT_BVH_DISPATCH 0
#define RT_BVH_DISPATCH_AVX512 0
#else
// RT_BVH_AVX512: 1 only in the third section of bvh/dispatch.hpp (the unit's
// own path may use AVX-512 too, under -march=native: the compiler's choice)
#define RT_BVH_AVX512 0

// RT_BVH_SSE: SSE2 is there (every x86-64 compiler) and rt::real is float.
#if !defined(RT_BVH_SSE)
#define RT_BVH_OWNS_SSE
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
#define RT_BVH_OWNS_AVX
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
#define RT_BVH_OWNS_AVX2
#if RT_BVH_AVX && defined(__AVX2__)
#define RT_BVH_AVX2 1
#else
#define RT_BVH_AVX2 0
#endif
#elif RT_BVH_AVX2 && (defined(__GNUC__) || defined(__clang__)) && !(RT_BVH_AVX && defined(__AVX2__))
#error "RT_BVH_AVX2=1 forces the 8-wide path, which needs rt::real = float and an AVX2 target (-mavx2); without RT_BVH_AVX2 rt picks the path at run time (bvh/dispatch.hpp)"
#endif

// RT_BVH_DISPATCH: this unit also compiles the 8-wide path for AVX2 CPUs and
// picks one at run time (see the top of this file): x86-64, SSE without
// AVX2, the three macros above left to rt, and a compiler that compiles a
// function for another target (g++ and clang++: #pragma GCC target / #pragma
// clang attribute; MSVC emits AVX2 in any function).
#if defined(RT_BVH_OWNS_SSE) && defined(RT_BVH_OWNS_AVX) && defined(RT_BVH_OWNS_AVX2) && RT_BVH_SSE && \
    !RT_BVH_AVX2 && \
    (((defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)) || (defined(_MSC_VER) && defined(_M_X64)))
#define RT_BVH_DISPATCH 1
#else
#define RT_BVH_DISPATCH 0
#endif

// RT_BVH_DISPATCH_AVX512: a dispatching unit of g++ or clang++ also compiles
// the 8-wide path a third time, for CPUs with AVX-512 (F, VL, BW, DQ, CD):
// the same operations on 256-bit registers, 32 of them, not 16, and with
// AVX-512's forms of them (as -march=native gives an AVX-512 machine; what
// that buys: docs/performance.md, "The path picked at run time").
// MSVC gets no third section: it would not use those registers without /arch.
#if RT_BVH_DISPATCH && (defined(__GNUC__) || defined(__clang__))
#define RT_BVH_DISPATCH_AVX512 1
#else
#define RT_BVH_DISPATCH_AVX512 0
#endif

// RT_BVH_ABI: the namespace of this width (see the top of this file), inline.
#if RT_BVH_AVX2
#define RT_BVH_ABI bvh_w8
#else
#define RT_BVH_ABI bvh_w4
#endif
#define RT_BVH_ABI_INLINE inline
#endif

// RT_BVH_ACCELERATOR_ABI: the inline namespace of rt::accelerator and of what
// holds one: its own where it dispatches (it holds either width), else the width's.
#if RT_BVH_DISPATCH
#define RT_BVH_ACCELERATOR_ABI bvh_dispatch
#else
#define RT_BVH_ACCELERATOR_ABI RT_BVH_ABI
#endif
