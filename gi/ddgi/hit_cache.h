// A per-frame cache of probe-ray hit shading. Within one frame the previous frame's probe
// field is constant, so hits that land in the same small world cell (a grid finer than the
// probe spacing, anchored at the world origin) with normals in the same octahedral bin can
// share one probe gather (and, in the `all` mode, one set of light-visibility tests).
//
// Each group's value is evaluated at one of its own hits: the one closest to the cell centre
// (ties to the lower hit index). That choice depends only on the set of hits, not on thread
// timing or probe order, so the result is deterministic and the same for a scrolled volume as
// for a fresh one. Hits on the two faces of a thin wall have opposite normals and never share.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

namespace voxgi {

class HitCache {
public:
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    // Normal bins per side of the octahedral square (16 bins over the sphere).
    static constexpr int kNormalBins = 4;

    // Groups `runs * runLength` hits (run r holds hits r * runLength ...);
    // `hit(run, i, &position, &normal)` returns false for hits that must not be cached
    // (misses, backfaces, black surfaces). Cells are `cellSize` wide.
    template <typename HitFn>
    void group(float cellSize, std::size_t runs, std::size_t runLength, HitFn&& hit);

    // The group of hit h (kNone: not cached) and the representative hit of a group.
    std::uint32_t groupOf(std::size_t h) const {
        std::uint32_t slot = hitGroup_[h];
        return slot == kNone ? kNone : slotGroup_[slot];
    }
    std::size_t groups() const { return representatives_.size(); }
    // Brings the slot-to-group entry of hit h into the cache ahead of groupOf(h).
    void prefetchGroupOf(std::size_t h) const {
        if (hitGroup_[h] != kNone) __builtin_prefetch(&slotGroup_[hitGroup_[h]]);
    }
    std::size_t representative(std::size_t g) const { return representatives_[g]; }

    // The cell-and-normal key of a point (0: outside the representable range) and its squared
    // distance to the cell centre.
    static std::uint64_t key(glm::vec3 position, glm::vec3 normal, float invCellSize, float* centreDistance2);

private:
    void reset(std::size_t capacity);
    // Inserts the hit into its key's slot; false when the table is too full (the caller grows it).
    bool insert(std::uint64_t key, std::uint64_t score, std::uint32_t* slot);
    void collect();  // slots in use -> dense group indices and representatives
    std::size_t home(std::uint64_t key) const;  // the key's first slot
    void prefetch(std::uint64_t key) const { __builtin_prefetch(&slots_[home(key)]); }

    // Key and best candidate share a cache line: one miss per insert.
    struct alignas(16) Slot {
        std::atomic<std::uint64_t> key;   // 0: empty
        std::atomic<std::uint64_t> best;  // (squared distance bits << 32) | hit
    };
    std::size_t capacity_ = 0;
    std::unique_ptr<Slot[]> slots_;
    std::atomic<std::size_t> used_{0};
    std::vector<std::uint32_t> hitGroup_;        // per hit: its slot
    std::vector<std::uint32_t> slotGroup_;       // per slot: dense group index
    std::vector<std::size_t> representatives_;   // per group
    std::size_t lastGroups_ = 0;
};

}  // namespace voxgi

#include "gi/ddgi/hit_cache_impl.h"
