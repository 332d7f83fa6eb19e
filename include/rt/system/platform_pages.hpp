// platform_pages.hpp - the one other call rt makes to the operating system:
// memory mapped for transparent huge pages, for the BVH's large arrays
// (bvh/parallel_fill.hpp says why and when). Kept apart from platform.hpp so
// that the fast path, and whoever includes rt/bvh/accelerator.hpp, never sees
// <windows.h> and its macros (near, far, ERROR...): only Linux needs a system
// header here.
//
//     if (rt::detail::maps_huge_pages)
//         if (void* p = rt::detail::map_huge_pages(bytes, 2 << 20)) { ...; rt::detail::unmap_huge_pages(p, bytes); }
#pragma once

#include <cstddef>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h> // mmap, madvise, munmap
#endif

namespace rt {
namespace detail {

#if defined(__linux__)
/// Linux maps memory with transparent huge pages on request (madvise(2),
/// MADV_HUGEPAGE): see bvh/parallel_fill.hpp for why and when.
inline constexpr bool maps_huge_pages = true;

/// `bytes` (a multiple of `alignment`) of fresh memory of its own mapping,
/// aligned to `alignment` and marked for huge pages (a hint: ignored where
/// transparent huge pages are off); nullptr when nothing can be mapped.
inline void* map_huge_pages(std::size_t bytes, std::size_t alignment)
{
    // one alignment more than asked, then the parts before and after the
    // first aligned run are given back (mmap() and munmap(), POSIX 2017)
    void* mapped = ::mmap(nullptr, bytes + alignment, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED)
        return nullptr;
    const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(mapped);
    const std::uintptr_t aligned = (start + alignment - 1) / alignment * alignment;
    if (aligned != start)
        ::munmap(mapped, aligned - start);
    ::munmap(reinterpret_cast<void*>(aligned + bytes), start + alignment - aligned); // at least a page
    ::madvise(reinterpret_cast<void*>(aligned), bytes, MADV_HUGEPAGE);
    return reinterpret_cast<void*>(aligned);
}

/// Gives back what map_huge_pages(bytes, ...) returned.
inline void unmap_huge_pages(void* memory, std::size_t bytes)
{
    ::munmap(memory, bytes);
}
#else
/// Other systems: macOS has no madvise(MADV_HUGEPAGE); Windows' large pages need
/// the "Lock pages in memory" privilege (Microsoft Learn, "Large-Page Support").
/// Large arrays come from operator new.
inline constexpr bool maps_huge_pages = false;
inline void* map_huge_pages(std::size_t, std::size_t)
{
    return nullptr;
}
inline void unmap_huge_pages(void*, std::size_t) {}
#endif

} // namespace detail
} // namespace rt
