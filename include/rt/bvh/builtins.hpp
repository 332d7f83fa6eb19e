// bvh/builtins.hpp - the compiler builtins the fast path uses, one name each,
// with a branch per compiler family and a portable fallback:
//
//     const int s = rt::detail::highest_bit(17u);   // 4: 2^4 <= 17 < 2^5
//     rt::detail::prefetch(&items[k + 8]);          // ask for a line we read soon
//     if (rt::detail::cpu_runs_avx2()) ...          // the 8-wide path may run (bvh/dispatch.hpp)
//     if (rt::detail::cpu_runs_avx512()) ...        // and its AVX-512 copy
//
// GCC and Clang: __builtin_clz, __builtin_prefetch, __builtin_cpu_init and
// __builtin_cpu_supports (GCC manual, "Other Built-in Functions" and "x86
// Built-in Functions"). MSVC: _BitScanReverse, on x86/x64 _mm_prefetch with
// _MM_HINT_T0, __cpuid, __cpuidex and _xgetbv (Microsoft Learn, "_BitScanReverse",
// "_mm_prefetch", "__cpuid, __cpuidex", "_xgetbv"); MSVC is not checked in CI.
// Elsewhere a loop, no prefetch (a hint: it never changes a result) and no AVX2.
#pragma once

#include <cstdint>

#if defined(_MSC_VER)
#include <intrin.h> // __cpuid, _BitScanReverse
#if defined(_M_X64) || defined(_M_IX86)
#include <immintrin.h> // _xgetbv, _mm_prefetch
#endif
#endif

namespace rt {
namespace detail {

/// The index of the highest set bit of x (x > 0): s with 2^s <= x < 2^(s + 1).
inline int highest_bit(std::uint32_t x)
{
#if defined(__GNUC__) || defined(__clang__)
    return 31 - __builtin_clz(x);
#elif defined(_MSC_VER)
    unsigned long index = 0;
    _BitScanReverse(&index, x);
    return int(index);
#else
    int s = 0;
    while ((x >> (s + 1)) != 0)
        ++s;
    return s;
#endif
}

/// Asks the processor to bring the cache line of `p` closer (read soon).
inline void prefetch(const void* p)
{
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p);
#elif defined(_MSC_VER) && (defined(_M_X64) || defined(_M_IX86))
    _mm_prefetch(static_cast<const char*>(p), _MM_HINT_T0);
#else
    (void)p;
#endif
}

/// Whether this CPU runs the 8-wide path (bvh/dispatch.hpp): the processor has
/// AVX2 and the operating system saves the 256-bit registers (XGETBV's bits 1
/// and 2), and with g++ and clang++, which compile that path with them, the
/// bit instructions BMI1, BMI2 and POPCNT (every AVX2 CPU has them:
/// the check is for virtual machines that hide some). GCC's and Clang's
/// __builtin_cpu_supports("avx2") checks AVX2 and the registers; MSVC reads CPUID
/// itself: leaf 1, ECX bit 27 (OSXSAVE) and bit 28 (AVX), XCR0 bits 1 and 2,
/// then leaf 7, EBX bit 5 (AVX2) (Intel SDM vol. 1, 14.3 "Detection of Intel
/// AVX instructions" and 14.7.1 for AVX2). False elsewhere (no x86).
inline bool cpu_runs_avx2()
{
#if defined(_MSC_VER) && (defined(_M_X64) || defined(_M_IX86))
    int info[4] = {0, 0, 0, 0};
    __cpuid(info, 0);
    if (info[0] < 7)
        return false;
    __cpuid(info, 1);
    const bool osxsave = (info[2] & (1 << 27)) != 0, avx = (info[2] & (1 << 28)) != 0;
    if (!osxsave || !avx || (_xgetbv(0) & 6) != 6)
        return false;
    __cpuidex(info, 7, 0);
    return (info[1] & (1 << 5)) != 0;
#elif (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
    __builtin_cpu_init(); // idempotent; needed only before constructors ran
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") &&
           __builtin_cpu_supports("popcnt");
#else
    return false;
#endif
}

/// Whether this CPU also runs the AVX-512 copy of the 8-wide path
/// (bvh/dispatch.hpp, compiled by g++ and clang++ only): cpu_runs_avx2() and
/// AVX-512 F, VL, BW, DQ and CD, with the operating system saving the opmask
/// and upper registers (GCC's and Clang's __builtin_cpu_supports checks XCR0
/// bits 5-7 too). False elsewhere.
inline bool cpu_runs_avx512()
{
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
    return cpu_runs_avx2() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
           __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512cd");
#else
    return false;
#endif
}

} // namespace detail
} // namespace rt
