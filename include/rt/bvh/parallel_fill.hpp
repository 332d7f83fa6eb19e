// bvh/parallel_fill.hpp - the build's large arrays, filled on threads, each
// thread writing its own part first.
//
// The first write to a fresh array of tens of megabytes costs a page fault
// per 4 KB page (the kernel clears the page), and a std::vector<T>(n) writes
// every element once (value-initialisation, zero for plain data) before the
// fill writes it again, on one thread. The build's arrays of plain data (the
// packed primitives, the leaf blocks) are therefore allocated with
// default_init_allocator, which leaves a plain-data element unwritten, and
// filled by fill_in_parallel, each thread writing contiguous parts: the page
// faults are shared by the threads as well (docs/performance.md, experiment 6).
//
//     std::vector<T, rt::detail::default_init_allocator<T>> out(n); // nothing written yet
//     rt::detail::fill_in_parallel(n, threads, [&](std::size_t begin, std::size_t end) {
//         for (std::size_t i = begin; i < end; ++i)
//             out[i] = make(i);                                       // every element, once
//     });
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

#include "../parallel.hpp"

namespace rt {
namespace detail {

/// std::allocator, except that an element constructed without arguments is
/// default-initialised (T x;), not value-initialised (T x{};): for plain
/// data, nothing is written. Such an element must be assigned before it is read.
template <class T>
struct default_init_allocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = default_init_allocator<U>;
    };

    default_init_allocator() = default;
    template <class U>
    default_init_allocator(const default_init_allocator<U>&) noexcept
    {
    }

    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
    {
        ::new (static_cast<void*>(p)) U;
    }

    template <class U, class... Args>
    void construct(U* p, Args&&... args)
    {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

/// Calls fill(begin, end) on contiguous ranges that cover [0, n) once, on
/// `threads` threads (see the top of this file); on this thread alone when
/// n is small or threads is 1. Ranges of at least `grain` elements.
template <class Fill>
void fill_in_parallel(std::size_t n, int threads, Fill&& fill, std::size_t grain = 16384)
{
    if (threads <= 1 || n < 2 * grain) {
        if (n > 0)
            fill(std::size_t(0), n);
        return;
    }
    // a few ranges per thread, so that one slow range does not hold the others back
    const std::size_t ranges = std::min(n / grain, std::size_t(threads) * 4);
    const std::size_t size = (n + ranges - 1) / ranges;
    parallel_for(ranges, threads, [&](std::size_t r, int) {
        const std::size_t begin = r * size;
        if (begin < n)
            fill(begin, std::min(n, begin + size));
    });
}

} // namespace detail
} // namespace rt
