// Storage for big tables that renderers read at random (textures, per-triangle hit records):
// allocations of 2 MiB and more are 2 MiB-aligned and marked for transparent huge pages.
//
// Why: a path tracer's hit reads a random triangle's record and a random texel. With 4 KiB
// pages each such read also misses the TLB, and under a hypervisor the page walk is
// two-dimensional; a software prefetch waits for the walk. On the 2-core VM, random reads of a
// 256 MiB table, 16 at a time between runs of arithmetic, cost 39 ns each without prefetches and
// 37 with them on 4 KiB pages, 42 and 28 on 2 MiB pages (docs/reference.md, "Paths sixteen at a
// time"). Where the kernel has transparent huge pages off, the hint is ignored and the pages
// stay 4 KiB.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace voxgi {

// `bytes` aligned to `alignment` (a power of two; at least 2 MiB-aligned and hinted for huge
// pages from 2 MiB on). Throws std::bad_alloc. Free with freeLarge.
void* allocateLarge(std::size_t bytes, std::size_t alignment);
void freeLarge(void* memory);

template <class T>
struct LargePageAllocator {
    using value_type = T;
    LargePageAllocator() = default;
    template <class U>
    LargePageAllocator(const LargePageAllocator<U>&) {}
    T* allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_alloc();
        return static_cast<T*>(allocateLarge(n * sizeof(T), alignof(T)));
    }
    void deallocate(T* p, std::size_t) { freeLarge(p); }
    template <class U>
    bool operator==(const LargePageAllocator<U>&) const { return true; }
    template <class U>
    bool operator!=(const LargePageAllocator<U>&) const { return false; }
};

template <class T>
using LargeVector = std::vector<T, LargePageAllocator<T>>;

}  // namespace voxgi
