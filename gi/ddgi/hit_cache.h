// A per-frame cache of probe-ray hit shading. Within one frame the previous frame's probe
// field is constant, so hits that land in the same small world cell (a grid finer than the
// probe spacing, anchored at the world origin) with normals in the same bin (24 over the
// sphere: the octant and the largest axis, at most 55 degrees apart within a bin) can
// share one probe gather (and, in the `all` mode, one set of light-visibility tests).
//
// Each group's value is evaluated at one of its own hits: the one closest to the cell centre
// (ties to the lower hit index). That choice depends only on the set of hits, not on thread
// timing or probe order, so the result is deterministic and the same for a scrolled volume as
// for a fresh one. Hits on the two faces of a thin wall have opposite normals and never share.
//
// Hits are added while they are traced (HitCache::Writer), each thread into its own table, so
// the grouping costs no second pass over the surfels and no cache line is shared between
// threads; finish() merges the tables into dense groups.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>
#include <tbb/enumerable_thread_specific.h>

namespace voxgi {

class HitCache {
    struct LocalTable;
    struct MergeTable;

public:
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;

    HitCache();
    ~HitCache();
    HitCache(const HitCache&) = delete;
    HitCache& operator=(const HitCache&) = delete;

    // Starts a frame of `hits` hits (numbered 0 ... hits - 1) in cells `cellSize` wide.
    void begin(float cellSize, std::size_t hits);

    // Adds hits from one thread: one writer per task, which binds the calling thread's table.
    // Every hit the frame's shading will ask about gets exactly one add() or skip(). Adds are
    // taken in batches: the keys of a batch are computed and their table slots prefetched
    // first, then placed, so the cache misses of a batch overlap one another.
    class Writer {
    public:
        explicit Writer(HitCache& cache);
        ~Writer();  // flushes
        Writer(const Writer&) = delete;
        Writer& operator=(const Writer&) = delete;
        void add(std::size_t h, glm::vec3 position, glm::vec3 normal);
        void skip(std::size_t h) { cache_.hitId_[h] = kNone; }

    private:
        static constexpr unsigned kBatch = 64;
        struct Pending {
            std::uint32_t hit;
            glm::vec3 position, normal;
        };
        struct Keyed {
            std::uint64_t key, hash;
            std::uint32_t d2, index;  // index: into pending_
        };
        void flush();
        void place(const Keyed& k, const Pending& p);
        HitCache& cache_;
        LocalTable& table_;
        Pending pending_[kBatch];
        Keyed keyed_[kBatch];
        unsigned count_ = 0;
    };

    // After every add of the frame (every writer destroyed): dense groups and representatives.
    void finish();

    // begin, add every hit for which `hit(run, i, &position, &normal)` is true (hit
    // run * runLength + i), finish.
    template <typename HitFn>
    void group(float cellSize, std::size_t runs, std::size_t runLength, HitFn&& hit);

    // The group of hit h (kNone: not cached) and the representative hit of a group.
    std::uint32_t groupOf(std::size_t h) const {
        std::uint32_t id = hitId_[h];
        if (id == kNone) return kNone;
        const std::uint32_t g = idGroup_[id];
        return partOffset_[g >> kPartShift] + (g & ((1u << kPartShift) - 1));
    }
    std::size_t groups() const { return representatives_.size(); }
    std::size_t representative(std::size_t g) const { return representatives_[g].hit; }
    // The same cell and normal bin's group in the previous finish() (kNone: none, or another
    // cell size), and a group's key (stable from frame to frame).
    std::uint32_t previousGroup(std::size_t g) const { return previousGroup_[g]; }
    std::uint64_t groupKey(std::size_t g) const { return groupKeys_[g]; }
    // Its position and normal as they were added: evaluating a group needs no look at the
    // (scattered, uncached) hit records.
    glm::vec3 representativePosition(std::size_t g) const { return representatives_[g].position; }
    glm::vec3 representativeNormal(std::size_t g) const { return representatives_[g].normal; }

    // The cell-and-normal key of a point (0: outside the representable range) and its squared
    // distance to the cell centre.
    static std::uint64_t key(glm::vec3 position, glm::vec3 normal, float invCellSize, float* centreDistance2);

private:
    static constexpr std::size_t kParts = 8;  // merge partitions (partOf: the top 3 bits of a hash)
    static constexpr int kPartShift = 28;         // idGroup_: partition << 28 | index in it

    LocalTable& localTable();
    std::uint32_t reserveIds();  // first id of a fresh block; kNone when the arrays are used up

    float invCellSize_ = 1.0f;
    std::vector<std::uint32_t> hitId_;      // per hit: the id of its key in its thread's table
    struct Candidate {
        glm::vec3 position{0.0f};
        std::uint32_t hit = 0;
        glm::vec3 normal{0.0f};
    };
    std::vector<Candidate> idBest_;         // per id: the candidate nearest the cell centre
    std::vector<std::uint32_t> idGroup_;    // per id: dense group index
    std::vector<Candidate> representatives_;  // per group
    std::vector<std::uint32_t> previousGroup_;  // per group
    std::vector<std::uint64_t> groupKeys_;      // per group
    float previousInvCellSize_ = 0.0f;         // of the tables the previous finish() built
    std::atomic<std::size_t> nextId_{0};
    std::unique_ptr<MergeTable> merged_;
    std::uint32_t partOffset_[kParts] = {}, previousPartOffset_[kParts] = {};
    tbb::enumerable_thread_specific<std::unique_ptr<LocalTable>> tables_;
};

}  // namespace voxgi

#include "gi/ddgi/hit_cache_impl.h"
