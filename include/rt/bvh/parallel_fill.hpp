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
// The arrays traversal reads (the wide nodes, the leaf blocks) and the
// build's own (its references) use large_array_allocator: an array of 8 MB or
// more is mapped on its own and marked for transparent huge pages (2 MB pages,
// where the kernel offers them, as Embree's allocator does:
// common/sys/alloc.cpp, os_malloc). With 4 KB pages the second-level TLB
// reaches 6 MB (1,536 entries), so incoherent rays through a larger tree wait
// for page walks, and a huge page is cleared faster than 512 small ones (the
// figures: docs/architecture.md, "Figures behind the comments").
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
#include <vector>

#include "../system/parallel.hpp"
#include "../system/platform_pages.hpp"

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

/// default_init_allocator for the large arrays of a tree and its build (see
/// the top of this file): from huge_page_threshold bytes on Linux, an array of
/// its own mapping, 2 MB aligned and marked MADV_HUGEPAGE (a hint: ignored
/// where transparent huge pages are off; platform_pages.hpp maps it); elsewhere, and
/// for smaller arrays, operator new, aligned to a cache line.
template <class T>
struct large_array_allocator : default_init_allocator<T> {
    template <class U>
    struct rebind {
        using other = large_array_allocator<U>;
    };

    large_array_allocator() = default;
    template <class U>
    large_array_allocator(const large_array_allocator<U>&) noexcept
    {
    }

    static constexpr std::size_t huge_page = std::size_t(2) << 20;
    /// Where huge pages pay (measured): beyond the 4 KB pages' TLB reach.
    static constexpr std::size_t huge_page_threshold = std::size_t(8) << 20;
    static constexpr std::align_val_t alignment{alignof(T) > 64 ? alignof(T) : 64};

    T* allocate(std::size_t n)
    {
        if (n > (std::size_t(-1) - 2 * huge_page) / sizeof(T)) // mapped_bytes(n) + huge_page must not wrap
            throw std::bad_array_new_length();
        if (maps_huge_pages && n * sizeof(T) >= huge_page_threshold) {
            void* mapped = map_huge_pages(mapped_bytes(n), huge_page); // 2 MB aligned
            if (mapped == nullptr)
                throw std::bad_alloc();
            return static_cast<T*>(mapped);
        }
        return static_cast<T*>(::operator new(n * sizeof(T), alignment));
    }

    void deallocate(T* p, std::size_t n) noexcept
    {
        if (maps_huge_pages && n * sizeof(T) >= huge_page_threshold) {
            unmap_huge_pages(p, mapped_bytes(n));
            return;
        }
        ::operator delete(p, alignment);
    }

    template <class U>
    bool operator==(const large_array_allocator<U>&) const noexcept
    {
        return true;
    }
    template <class U>
    bool operator!=(const large_array_allocator<U>&) const noexcept
    {
        return false;
    }

private:
    static std::size_t mapped_bytes(std::size_t n) { return (n * sizeof(T) + huge_page - 1) / huge_page * huge_page; }
};

/// A vector of large_array_allocator.
template <class T>
using large_array = std::vector<T, large_array_allocator<T>>;

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
