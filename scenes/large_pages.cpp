#include "scenes/large_pages.h"

#include <algorithm>
#include <cstdlib>

#include <sys/mman.h>

namespace voxgi {

namespace {
constexpr std::size_t kHugePage = std::size_t(2) << 20;
}

void* allocateLarge(std::size_t bytes, std::size_t alignment) {
    alignment = std::max<std::size_t>(alignment, alignof(std::max_align_t));
    if (bytes >= kHugePage) alignment = std::max(alignment, kHugePage);
    // aligned_alloc wants a multiple of the alignment; a huge table gives up at most one
    // page's rounding (untouched, it is never backed).
    const std::size_t rounded = (std::max<std::size_t>(bytes, 1) + alignment - 1) / alignment * alignment;
    if (rounded < bytes) throw std::bad_alloc();
    void* memory = std::aligned_alloc(alignment, rounded);
    if (!memory) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    // A hint: refused (transparent huge pages off, or none free) it changes nothing.
    if (bytes >= kHugePage) madvise(memory, rounded, MADV_HUGEPAGE);
#endif
    return memory;
}

void freeLarge(void* memory) { std::free(memory); }

}  // namespace voxgi
