// bvh/dispatch.hpp - the 8-wide AVX2 path compiled a second time, in a unit
// whose target lacks AVX2, for rt::accelerator to walk where the CPU has it
// (run-time dispatch), and with g++ and clang++ a third time with AVX-512
// added, for CPUs that have that too.
//
// A program built as most are (-O2, no -march) targets x86-64's SSE2 and gets
// 4-wide nodes (layout.hpp), slower than the 8-wide path on an AVX2 machine
// (docs/architecture.md, "Figures behind the comments"). Where RT_BVH_DISPATCH
// is 1 (bvh/abi_begin.hpp: x86-64, g++, clang++ or MSVC, rt::real = float, the
// target without AVX2, RT_BVH_AVX2 not set), this file compiles the
// width-dependent headers (layout, node_test, descend, leaf_test,
// wide_collapse and bvh/bvh.hpp) once more:
//
//  - in a section whose macros say AVX2 (RT_BVH_AVX2_SECTION: abi_begin.hpp
//    then gives RT_BVH_AVX2 = 1 and RT_BVH_ABI = bvh_w8), so each header's
//    guard lets its 8-wide version through (one guard per width);
//  - under target("avx2,bmi,bmi2,popcnt"): `#pragma GCC target` (g++)
//    or `#pragma clang attribute` (clang++), which give every function the
//    section defines, lambdas and templates included, the right to use AVX2,
//    through it AVX and SSE4, and the bit instructions every AVX2 CPU has
//    (x86-64-v3 less FMA, LZCNT and MOVBE: the walk's variable shifts and bit counts
//    are single instructions, shlx and popcnt, as under -march=native; what
//    they buy is in docs/performance.md, "The path picked at run time").
//    clang++ does not define __AVX2__ there, g++ does: nothing here reads it.
//    MSVC compiles AVX2 intrinsics in any function and needs none (not
//    checked in CI);
//  - in the namespaces rt::bvh_w8 and rt::detail::bvh_w8, not inline, so that
//    rt::bvh, rt::detail::bvh_node... stay the unit's 4-wide ones (layout.hpp links
//    the section's names to its own width);
//  - and with g++ and clang++ once more, in rt::bvh_w8_avx512 (RT_BVH_AVX512_SECTION
//    too), under the same target plus AVX-512 F, VL, BW, DQ and CD: the same
//    256-bit operations with 32 registers, not 16, and AVX-512's forms of
//    some, which an AVX-512 machine's -march=native build had had alone
//    (without this section the AVX2 one fell behind such a build on the
//    Cornell box's shadow rays: docs/performance.md, "The path picked at
//    run time"). rt::accelerator walks it where
//    detail::cpu_runs_avx512() says yes.
//
// Why it is safe:
//  - No FMA in the AVX2 target: no compiler can fuse a b - c d there, so the
//    8-wide walk computes the bits of the 4-wide one and of the scalar one
//    (tests/library_dispatch.cpp compares them) without -ffp-contract=off.
//    AVX-512 has fused forms: its section turns contraction off itself
//    (#pragma GCC optimize, #pragma clang fp), whatever the unit's flags.
//  - Only rt::accelerator calls into a section, and only after
//    detail::cpu_runs_avx2() (builtins.hpp: AVX2 and those bit instructions),
//    or cpu_runs_avx512(), said yes: an 8-wide tree is built, walked and
//    destroyed only on such a CPU (it is held apart, in a std::optional, never
//    default-constructed on another path; tests/check_avx_confined.py checks
//    that no such instruction leaks out of the sections' namespaces).
//  - What the section calls outside it (the watertight test's check in
//    double, std::, the build's binning) is compiled for the unit's target,
//    which an AVX2 CPU runs too; the compiler may inline it into the
//    section, never the reverse (a target mismatch it refuses).
//  - One unit compiled with -mavx2 and one dispatching both define
//    rt::bvh_w8's functions, from the same text with the same macros; the
//    linker may keep either, and either runs where the 8-wide path runs
//    (the dispatching copy's bit instructions too: every AVX2 CPU has them).
//    rt::accelerator itself differs (it holds either width), so a
//    dispatching unit names it rt::bvh_dispatch::accelerator
//    (RT_BVH_ACCELERATOR_ABI, abi_begin.hpp; tests/library_mixed_targets.cpp).
// (#pragma once: the default section is bvh.hpp's, the other two this file's.)
#pragma once

#include "bvh.hpp"      // the unit's own width first: rt::bvh
#include "builtins.hpp" // detail::cpu_runs_avx2

#include "abi_begin.hpp" // RT_BVH_DISPATCH, RT_BVH_DISPATCH_AVX512
#if RT_BVH_DISPATCH
#if RT_BVH_DISPATCH_AVX512
#define RT_BVH_AVX512_WANTED // (simd_end.hpp takes the others away)
#endif
#include "simd_end.hpp"
#include <immintrin.h> // before the section, so that no declaration of it takes the section's target

#define RT_BVH_AVX2_SECTION
#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,bmi,bmi2,popcnt"))), apply_to = function)
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC target("avx2,bmi,bmi2,popcnt")
#endif

#include "bvh.hpp" // now the 8-wide path, in rt::bvh_w8

#if defined(__clang__)
#pragma clang attribute pop
#elif defined(__GNUC__)
#pragma GCC pop_options
#endif
#undef RT_BVH_AVX2_SECTION

#if defined(RT_BVH_AVX512_WANTED)
#undef RT_BVH_AVX512_WANTED
// The third section: the 8-wide path once more, in rt::bvh_w8_avx512, for
// CPUs with AVX-512 (abi_begin.hpp, RT_BVH_DISPATCH_AVX512). AVX-512 brings
// fused multiply-adds (their EVEX forms), so contraction is turned off here,
// whatever the unit's -ffp-contract: each operation rounds as in the other
// paths, and the hits stay bit for bit theirs (tests/library_dispatch.cpp;
// without the pragma, at g++'s default -ffp-contract=fast, 15,965 of its
// 20,000 records of the bunny differed from the other paths').
// Arithmetic on 256-bit vectors only, as in the AVX2 section: 512-bit
// arithmetic slows the clock of some CPUs (g++: prefer-vector-width=256;
// clang++ prefers 256 there; g++ may still copy a structure with 512-bit moves).
#define RT_BVH_AVX2_SECTION
#define RT_BVH_AVX512_SECTION
#if defined(__clang__)
#pragma clang attribute push(                                                                                  \
    __attribute__((target("avx2,bmi,bmi2,popcnt,avx512f,avx512vl,avx512bw,avx512dq,avx512cd"))), apply_to = function)
#pragma float_control(push)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC target("avx2,bmi,bmi2,popcnt,avx512f,avx512vl,avx512bw,avx512dq,avx512cd,prefer-vector-width=256")
#pragma GCC optimize("fp-contract=off")
#endif

#include "bvh.hpp" // the 8-wide path, in rt::bvh_w8_avx512

#if defined(__clang__)
#pragma float_control(pop)
#pragma clang attribute pop
#elif defined(__GNUC__)
#pragma GCC pop_options
#endif
#undef RT_BVH_AVX512_SECTION
#undef RT_BVH_AVX2_SECTION
#endif
#else
#include "simd_end.hpp"
#endif
