// HitCache::group (a template: the per-hit accessor is inlined into the grouping loop).
#pragma once

#include <algorithm>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace voxgi {

template <typename HitFn>
void HitCache::group(float cellSize, std::size_t runs, std::size_t runLength, HitFn&& hit) {
    const float inv = 1.0f / cellSize;
    hitGroup_.resize(runs * runLength);
    // Sized from the last frame's group count; a frame with many more groups regrows and
    // regroups, which gives the same groups (the choice is order-independent).
    std::size_t capacity = 1024;
    while (capacity < 2 * lastGroups_) capacity *= 2;
    for (;;) {
        reset(capacity);
        std::atomic<bool> full{false};
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs, 4), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t run = r.begin(); run != r.end(); ++run) {
                if (full.load(std::memory_order_relaxed)) return;
                std::uint32_t* slots = &hitGroup_[run * runLength];
                // Keys of a batch first, with their table lines prefetched, then the inserts:
                // the table misses overlap instead of queueing one by one.
                constexpr std::size_t kBatch = 32;
                std::uint64_t keys[kBatch], scores[kBatch];
                for (std::size_t first = 0; first < runLength; first += kBatch) {
                    const std::size_t count = std::min(kBatch, runLength - first);
                    for (std::size_t b = 0; b < count; ++b) {
                        const std::size_t i = first + b;
                        glm::vec3 p, n;
                        float d2 = 0.0f;
                        keys[b] = hit(run, i, &p, &n) ? key(p, n, inv, &d2) : 0;
                        std::uint32_t bits;
                        std::memcpy(&bits, &d2, sizeof bits);  // non-negative floats order like their bits
                        scores[b] = (std::uint64_t(bits) << 32) | std::uint64_t(run * runLength + i);
                        if (keys[b]) prefetch(keys[b]);
                    }
                    for (std::size_t b = 0; b < count; ++b) {
                        if (keys[b] == 0) slots[first + b] = kNone;
                        else if (!insert(keys[b], scores[b], &slots[first + b])) full = true;
                    }
                }
            }
        });
        if (!full) break;
        capacity *= 4;
    }
    collect();
}

}  // namespace voxgi
