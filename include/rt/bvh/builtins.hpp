// bvh/builtins.hpp - the two compiler builtins the fast path's build uses, one
// name each, with a branch per compiler family and a portable fallback:
//
//     const int s = rt::detail::highest_bit(17u);   // 4: 2^4 <= 17 < 2^5
//     rt::detail::prefetch(&items[k + 8]);          // ask for a line we read soon
//
// GCC and Clang: __builtin_clz and __builtin_prefetch (GCC manual, "Other
// Built-in Functions"). MSVC: _BitScanReverse and, on x86/x64, _mm_prefetch with
// _MM_HINT_T0 (Microsoft Learn, "_BitScanReverse", "_mm_prefetch"); MSVC is not
// checked in CI. Elsewhere a loop, and no prefetch (a hint: it never changes a result).
#pragma once

#include <cstdint>

#if defined(_MSC_VER) && !defined(__clang__)
#include <intrin.h>
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

} // namespace detail
} // namespace rt
