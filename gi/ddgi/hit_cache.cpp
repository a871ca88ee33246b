#include "gi/ddgi/hit_cache.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <emmintrin.h>

#include <tbb/task_arena.h>

#include "gi/sampling/hash.h"

namespace voxgi {

namespace {
constexpr int kCellBits = 19;  // per axis, offset binary: 3 x 19 bits and a 5-bit normal bin
constexpr std::int64_t kCellRange = std::int64_t(1) << (kCellBits - 1);
// Ids are handed to the threads' tables in blocks, so they stay dense (the per-id arrays stay
// in cache) without a shared counter per key.
constexpr std::uint32_t kIdBlock = 256;

// Open addressing over a power-of-two slot array holding indices into an entry list, so
// entries keep their index when the slots are rebuilt; at most 70 % full.
template <typename Entry>
class KeyTable {
public:
    void clear(std::size_t expected) {
        std::size_t capacity = 1024;
        while (capacity * 7 < expected * 10 * 2) capacity *= 2;
        if (slots_.size() != capacity) slots_.assign(capacity, Slot{});
        else std::fill(slots_.begin(), slots_.end(), Slot{});
        entries_.clear();
    }
    // The entry of `key`, or null; `slot` receives where it is or would go.
    Entry* find(std::uint64_t key, std::size_t* slot) {
        if (slots_.empty()) return nullptr;
        const std::size_t mask = slots_.size() - 1;
        for (std::size_t i = std::size_t(mix64(key)) & mask;; i = (i + 1) & mask) {
            const Slot& s = slots_[i];
            if (s.key == key) return &entries_[s.entry];
            if (s.key == 0) {
                *slot = i;
                return nullptr;
            }
        }
    }
    // Adds a key that find() did not find at `slot`.
    Entry& insert(std::uint64_t key, std::size_t slot, const Entry& entry) {
        if ((entries_.size() + 1) * 10 > slots_.size() * 7) {
            grow();
            find(key, &slot);
        }
        slots_[slot] = Slot{key, std::uint32_t(entries_.size())};
        entries_.push_back(entry);
        return entries_.back();
    }
    const std::vector<Entry>& entries() const { return entries_; }
    std::vector<Entry>& entries() { return entries_; }

private:
    struct Slot {
        std::uint64_t key = 0;  // 0: empty
        std::uint32_t entry = 0;
    };
    void grow() {
        slots_.assign(slots_.size() * 2, Slot{});
        const std::size_t mask = slots_.size() - 1;
        for (std::size_t e = 0; e < entries_.size(); ++e) {
            std::size_t i = std::size_t(mix64(entries_[e].key)) & mask;
            while (slots_[i].key != 0) i = (i + 1) & mask;
            slots_[i] = Slot{entries_[e].key, std::uint32_t(e)};
        }
    }
    std::vector<Slot> slots_;
    std::vector<Entry> entries_;
};

// Which merge partition a key belongs to (a multiplicative hash's top bits).
std::size_t partOf(std::uint64_t key) { return std::size_t((key * 0x9E3779B97F4A7C15ull) >> 61); }

struct GroupEntry {
    std::uint64_t key;
    std::uint32_t d2;  // bits of the best candidate's squared distance to the cell centre
    std::uint32_t id;  // the table entry holding that candidate
};
}  // namespace

// One thread's keys: open addressing, at most 70 % full. A slot holds everything an add
// reads, so an add that finds its key touches one cache line.
struct HitCache::LocalTable {
    struct Slot {
        std::uint64_t key = 0;  // 0: empty
        std::uint32_t id = 0;
        std::uint32_t d2 = 0;   // bits of the best candidate's squared distance to the centre
    };
    std::vector<Slot> slots;
    std::size_t used = 0, lastUsed = 0;
    std::uint32_t nextId = 0, idEnd = 0;  // the block of ids this table hands out

    void clear() {
        lastUsed = std::max(lastUsed, used);
        std::size_t capacity = 1024;
        while (capacity * 7 < lastUsed * 10) capacity *= 2;
        if (slots.size() != capacity) slots.assign(capacity, Slot{});
        else std::fill(slots.begin(), slots.end(), Slot{});
        used = 0;
        nextId = idEnd = 0;
    }
    std::size_t home(std::uint64_t key) const { return std::size_t(mix64(key)) & (slots.size() - 1); }
    void grow() {
        std::vector<Slot> old(slots.size() * 2);
        old.swap(slots);
        const std::size_t mask = slots.size() - 1;
        for (const Slot& s : old) {
            if (s.key == 0) continue;
            std::size_t i = home(s.key);
            while (slots[i].key != 0) i = (i + 1) & mask;
            slots[i] = s;
        }
    }
};

struct HitCache::MergeTable {
    KeyTable<GroupEntry> frames[2][kParts];  // this finish()'s partitions and the previous one's
    int current = 0;
    std::vector<std::vector<GroupEntry>> buckets;  // table * kParts + partition
};

HitCache::HitCache() = default;
HitCache::~HitCache() = default;

std::uint64_t HitCache::key(glm::vec3 p, glm::vec3 n, float inv, float* centreDistance2) {
    // Every probe-ray hit comes through here, so it is kept to a few dozen instructions: the
    // cells in one packed multiply-add and truncation (the offset makes truncation the floor
    // and the range check one shift), the normal's bin from its signs and largest axis.
    const __m128 offset = _mm_set1_ps(float(kCellRange));
    const __m128 scaled = _mm_mul_ps(_mm_setr_ps(p.x, p.y, p.z, 0.0f), _mm_set1_ps(inv));
    const __m128i c = _mm_cvttps_epi32(_mm_add_ps(scaled, offset));
    // Inside [0, 2 kCellRange) on every axis; NaN and overflow convert to 0x80000000.
    if (_mm_movemask_epi8(_mm_cmpeq_epi32(_mm_srli_epi32(c, kCellBits), _mm_setzero_si128())) != 0xFFFF) return 0;
    // The offset sum is rounded; the distance to the centre is taken from the exact product
    // (the cell corner c - offset is an exact integer), so near-ties stay rare.
    const __m128 d = _mm_sub_ps(_mm_sub_ps(scaled, _mm_sub_ps(_mm_cvtepi32_ps(c), offset)), _mm_set1_ps(0.5f));
    const __m128 dd = _mm_mul_ps(d, d);
    *centreDistance2 = _mm_cvtss_f32(_mm_add_ss(_mm_add_ss(dd, _mm_shuffle_ps(dd, dd, 1)), _mm_movehl_ps(dd, dd)));
    const std::uint64_t cx = std::uint32_t(_mm_cvtsi128_si32(c)),
                        cy = std::uint32_t(_mm_cvtsi128_si32(_mm_shuffle_epi32(c, 1))),
                        cz = std::uint32_t(_mm_cvtsi128_si32(_mm_shuffle_epi32(c, 2)));

    const float ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
    const int axis = ax >= ay ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
    const int signs = int(n.x < 0.0f) | int(n.y < 0.0f) << 1 | int(n.z < 0.0f) << 2;
    const std::uint64_t bin = std::uint64_t(1 + signs * 3 + axis);  // 1 ... 24: a key is never 0
    return (((cx << kCellBits | cy) << kCellBits | cz) << 5) | bin;
}

void HitCache::begin(float cellSize, std::size_t hits) {
    if (hits >= std::size_t(kNone)) throw std::length_error("DDGI hit cache: more than 2^32 - 1 hits in one frame");
    invCellSize_ = 1.0f / cellSize;
    // No clearing: every hit is written by add() or skip(), every id by the add that makes it.
    hitId_.resize(hits);
    // Each table wastes less than a block; more threads than expected only lose the cache
    // for their last hits (reserveIds runs dry), never correctness.
    const std::size_t ids = std::min<std::size_t>(
        hits + std::size_t(kIdBlock) * (std::size_t(tbb::this_task_arena::max_concurrency()) + 8), kNone);
    idBest_.resize(ids);
    idGroup_.resize(ids);
    nextId_.store(0, std::memory_order_relaxed);
    for (std::unique_ptr<LocalTable>& t : tables_)
        if (t) t->clear();
}

HitCache::LocalTable& HitCache::localTable() {
    std::unique_ptr<LocalTable>& t = tables_.local();
    if (!t) {
        t = std::make_unique<LocalTable>();
        t->clear();
    }
    return *t;
}

std::uint32_t HitCache::reserveIds() {
    const std::size_t first = nextId_.fetch_add(kIdBlock, std::memory_order_relaxed);
    return first + kIdBlock <= idBest_.size() ? std::uint32_t(first) : kNone;
}

HitCache::Writer::Writer(HitCache& cache) : cache_(cache), table_(cache.localTable()) {}

HitCache::Writer::~Writer() { flush(); }

void HitCache::Writer::add(std::size_t h, glm::vec3 position, glm::vec3 normal) {
    Pending& p = pending_[count_];
    p.hit = std::uint32_t(h);
    p.position = position;
    p.normal = normal;
    if (++count_ == kBatch) flush();
}

void HitCache::Writer::flush() {
    // Keys first, each slot prefetched as soon as its key is known; by the time the batch is
    // placed, the first slots have arrived.
    const std::size_t mask = table_.slots.size() - 1;
    unsigned keyed = 0;
    for (unsigned i = 0; i < count_; ++i) {
        const Pending& p = pending_[i];
        float d2 = 0.0f;
        const std::uint64_t k = key(p.position, p.normal, cache_.invCellSize_, &d2);
        if (k == 0) {
            skip(p.hit);
            continue;
        }
        Keyed& q = keyed_[keyed++];
        q.key = k;
        q.hash = mix64(k);
        __builtin_prefetch(&table_.slots[std::size_t(q.hash) & mask]);
        std::memcpy(&q.d2, &d2, sizeof q.d2);  // non-negative floats order like their bits
        q.index = i;
    }
    for (unsigned i = 0; i < keyed; ++i) place(keyed_[i], pending_[keyed_[i].index]);
    count_ = 0;
}

void HitCache::Writer::place(const Keyed& k, const Pending& p) {
    LocalTable& t = table_;
    std::size_t mask = t.slots.size() - 1;
    std::size_t i = std::size_t(k.hash) & mask;
    for (;; i = (i + 1) & mask) {
        LocalTable::Slot& s = t.slots[i];
        if (s.key == k.key) {
            // Ties go to the lower hit index, so the choice does not depend on the order of adds.
            if (k.d2 < s.d2 || (k.d2 == s.d2 && p.hit < cache_.idBest_[s.id].hit)) {
                s.d2 = k.d2;
                cache_.idBest_[s.id] = Candidate{p.position, p.hit, p.normal};
            }
            cache_.hitId_[p.hit] = s.id;
            return;
        }
        if (s.key == 0) break;
    }
    if ((t.used + 1) * 10 > t.slots.size() * 7) {
        t.grow();
        mask = t.slots.size() - 1;
        for (i = std::size_t(k.hash) & mask; t.slots[i].key != 0; i = (i + 1) & mask) {
        }
    }
    if (t.nextId == t.idEnd) {
        const std::uint32_t first = cache_.reserveIds();
        if (first == kNone) {
            cache_.hitId_[p.hit] = kNone;
            return;
        }
        t.nextId = first;
        t.idEnd = first + kIdBlock;
    }
    const std::uint32_t id = t.nextId++;
    t.slots[i] = LocalTable::Slot{k.key, id, k.d2};
    ++t.used;
    cache_.idBest_[id] = Candidate{p.position, p.hit, p.normal};
    cache_.hitId_[p.hit] = id;
}

void HitCache::finish() {
    // Merge the threads' tables: one group per key, the best candidate over all of them. Each
    // table's slots are first scattered by key into kParts buckets (one pass, sequential
    // writes), then each partition is merged in a table small enough to stay in cache; a
    // group's index is its partition's offset plus its place there (idGroup_ holds both until
    // groupOf adds them).
    std::vector<const LocalTable*> tables;
    std::size_t total = 0;
    for (const std::unique_ptr<LocalTable>& t : tables_)
        if (t) {
            tables.push_back(t.get());
            total += t->used;
        }
    if (!merged_) merged_ = std::make_unique<MergeTable>();
    MergeTable& m = *merged_;
    m.current ^= 1;
    KeyTable<GroupEntry>* parts = m.frames[m.current];
    KeyTable<GroupEntry>* previous = m.frames[m.current ^ 1];
    const bool samePlaces = previousInvCellSize_ == invCellSize_;
    previousInvCellSize_ = invCellSize_;
    std::copy(partOffset_, partOffset_ + kParts, previousPartOffset_);
    m.buckets.resize(tables.size() * kParts);
    tbb::parallel_for(std::size_t(0), tables.size(), [&](std::size_t t) {
        std::vector<GroupEntry>* buckets = &m.buckets[t * kParts];
        for (std::size_t part = 0; part < kParts; ++part) buckets[part].clear();
        for (const LocalTable::Slot& s : tables[t]->slots)
            if (s.key != 0) buckets[partOf(s.key)].push_back(GroupEntry{s.key, s.d2, s.id});
    });
    tbb::parallel_for(std::size_t(0), kParts, [&](std::size_t part) {
        KeyTable<GroupEntry>& merged = parts[part];  // kept: its memory is reused
        merged.clear(total / kParts + 16);
        for (std::size_t t = 0; t < tables.size(); ++t)
            for (const GroupEntry& e : m.buckets[t * kParts + part]) {
                std::size_t slot = 0;
                GroupEntry* g = merged.find(e.key, &slot);
                // The candidate's hit index is only read to break a tie (rare): it is in
                // another, uncached array.
                if (!g) g = &merged.insert(e.key, slot, e);
                else if (e.d2 < g->d2 || (e.d2 == g->d2 && idBest_[e.id].hit < idBest_[g->id].hit)) *g = e;
                idGroup_[e.id] = std::uint32_t(part << kPartShift) | std::uint32_t(g - merged.entries().data());
            }
    });
    std::size_t groups = 0;
    for (std::size_t part = 0; part < kParts; ++part) {
        partOffset_[part] = std::uint32_t(groups);
        groups += parts[part].entries().size();
    }
    if (groups >= (std::size_t(1) << kPartShift)) throw std::length_error("DDGI hit cache: too many groups in one frame");
    representatives_.resize(groups);
    previousGroup_.resize(groups);
    groupKeys_.resize(groups);
    tbb::parallel_for(std::size_t(0), kParts, [&](std::size_t part) {
        std::vector<GroupEntry>& entries = parts[part].entries();
        for (std::size_t j = 0; j < entries.size(); ++j) {
            const std::size_t g = partOffset_[part] + j;
            representatives_[g] = idBest_[entries[j].id];
            groupKeys_[g] = entries[j].key;
            std::size_t slot = 0;
            const GroupEntry* before = samePlaces ? previous[part].find(entries[j].key, &slot) : nullptr;
            previousGroup_[g] = before ? previousPartOffset_[part] + std::uint32_t(before - previous[part].entries().data())
                                       : kNone;
        }
    });
}

}  // namespace voxgi
