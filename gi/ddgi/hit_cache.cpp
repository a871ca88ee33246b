#include "gi/ddgi/hit_cache.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>


namespace voxgi {

namespace {
constexpr std::int64_t kCellRange = std::int64_t(1) << 19;  // 20 bits per axis, offset binary

std::uint64_t mix64(std::uint64_t x) {  // splitmix64's finalizer
    x ^= x >> 30;
    x *= 0xBF58476D1CE4E5B9ull;
    x ^= x >> 27;
    x *= 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}
}  // namespace

std::uint64_t HitCache::key(glm::vec3 p, glm::vec3 n, float inv, float* centreDistance2) {
    glm::vec3 scaled = p * inv;
    glm::vec3 cell = glm::floor(scaled);
    std::uint64_t k = 0;
    for (int a = 0; a < 3; ++a) {
        if (!(std::abs(cell[a]) < float(kCellRange))) return 0;  // also NaN
        k = (k << 20) | std::uint64_t(std::int64_t(cell[a]) + kCellRange);
    }
    // The octahedral square of n (oct::encode, with one reciprocal), cut into bins.
    float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    float invL1 = l1 > 0.0f ? 1.0f / l1 : 0.0f;
    float ex = n.x * invL1, ey = n.y * invL1;
    if (n.z < 0.0f) {
        float fx = (1.0f - std::abs(ey)) * (ex >= 0.0f ? 1.0f : -1.0f);
        ey = (1.0f - std::abs(ex)) * (ey >= 0.0f ? 1.0f : -1.0f);
        ex = fx;
    }
    int bx = std::clamp(int((ex * 0.5f + 0.5f) * float(kNormalBins)), 0, kNormalBins - 1);
    int by = std::clamp(int((ey * 0.5f + 0.5f) * float(kNormalBins)), 0, kNormalBins - 1);
    glm::vec3 d = scaled - cell - 0.5f;
    *centreDistance2 = glm::dot(d, d);
    return (k << 4) | std::uint64_t(by * kNormalBins + bx);
}

void HitCache::reset(std::size_t capacity) {
    if (capacity != capacity_) {
        capacity_ = capacity;
        slots_.reset(new Slot[capacity]);
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, capacity_, 16384), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            slots_[i].key.store(0, std::memory_order_relaxed);
            slots_[i].best.store(~std::uint64_t(0), std::memory_order_relaxed);
        }
    });
    used_.store(0, std::memory_order_relaxed);
}

std::size_t HitCache::home(std::uint64_t key) const { return std::size_t(mix64(key)) & (capacity_ - 1); }

bool HitCache::insert(std::uint64_t key, std::uint64_t score, std::uint32_t* slot) {
    const std::size_t mask = capacity_ - 1;
    std::size_t i = home(key);
    for (;;) {
        std::uint64_t k = slots_[i].key.load(std::memory_order_relaxed);
        if (k == 0) {
            // At most 70 % full: linear probing stays short, and a full table is never searched.
            if (used_.fetch_add(1, std::memory_order_relaxed) >= capacity_ / 10 * 7) return false;
            if (slots_[i].key.compare_exchange_strong(k, key, std::memory_order_relaxed)) break;
            used_.fetch_sub(1, std::memory_order_relaxed);  // another thread took the slot
        }
        if (k == key) break;
        i = (i + 1) & mask;
    }
    std::atomic<std::uint64_t>& best = slots_[i].best;
    std::uint64_t current = best.load(std::memory_order_relaxed);
    while (score < current && !best.compare_exchange_weak(current, score, std::memory_order_relaxed)) {
    }
    *slot = std::uint32_t(i);
    return true;
}

void HitCache::collect() {
    slotGroup_.assign(capacity_, kNone);
    representatives_.clear();
    for (std::size_t i = 0; i < capacity_; ++i) {
        if (slots_[i].key.load(std::memory_order_relaxed) == 0) continue;
        slotGroup_[i] = std::uint32_t(representatives_.size());
        representatives_.push_back(std::size_t(slots_[i].best.load(std::memory_order_relaxed) & 0xFFFFFFFFu));
    }
    lastGroups_ = representatives_.size();
}

}  // namespace voxgi
