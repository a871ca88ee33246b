#include "gi/ddgi/hit_cache.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

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

struct GroupEntry {
    std::uint64_t key;
    std::uint64_t best;  // (squared distance bits << 32) | hit
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

    void clear() {
        lastUsed = std::max(lastUsed, used);
        std::size_t capacity = 1024;
        while (capacity * 7 < lastUsed * 10) capacity *= 2;
        if (slots.size() != capacity) slots.assign(capacity, Slot{});
        else std::fill(slots.begin(), slots.end(), Slot{});
        used = 0;
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

HitCache::HitCache() = default;
HitCache::~HitCache() = default;

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

void HitCache::begin(float cellSize, std::size_t hits) {
    if (hits >= std::size_t(kNone)) throw std::length_error("DDGI hit cache: more than 2^32 - 1 hits in one frame");
    invCellSize_ = 1.0f / cellSize;
    // No clearing: every hit is written by add() or skip(), every id by the add that makes it.
    hitId_.resize(hits);
    idBestHit_.resize(hits);
    idGroup_.resize(hits);
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

HitCache::Writer::Writer(HitCache& cache) : cache_(cache), table_(cache.localTable()) {}

HitCache::Writer::~Writer() {
    for (; count_ > 0; --count_, first_ = (first_ + 1) % kDelay) place(pending_[first_]);
}

void HitCache::Writer::add(std::size_t h, glm::vec3 position, glm::vec3 normal) {
    float d2 = 0.0f;
    const std::uint64_t k = key(position, normal, cache_.invCellSize_, &d2);
    if (k == 0) {
        skip(h);
        return;
    }
    Pending p{k, 0, std::uint32_t(h)};
    std::memcpy(&p.d2, &d2, sizeof p.d2);  // non-negative floats order like their bits
    __builtin_prefetch(&table_.slots[table_.home(k)]);
    if (count_ == kDelay) {
        place(pending_[first_]);
        pending_[first_] = p;
        first_ = (first_ + 1) % kDelay;
    } else {
        pending_[(first_ + count_++) % kDelay] = p;
    }
}

void HitCache::Writer::place(const Pending& p) {
    LocalTable& t = table_;
    std::size_t mask = t.slots.size() - 1;
    std::size_t i = t.home(p.key);
    for (;; i = (i + 1) & mask) {
        LocalTable::Slot& s = t.slots[i];
        if (s.key == p.key) {
            // Ties go to the lower hit index, so the choice does not depend on the order of adds.
            if (p.d2 < s.d2 || (p.d2 == s.d2 && p.hit < cache_.idBestHit_[s.id])) {
                s.d2 = p.d2;
                cache_.idBestHit_[s.id] = p.hit;
            }
            cache_.hitId_[p.hit] = s.id;
            return;
        }
        if (s.key == 0) break;
    }
    if ((t.used + 1) * 10 > t.slots.size() * 7) {
        t.grow();
        mask = t.slots.size() - 1;
        for (i = t.home(p.key); t.slots[i].key != 0; i = (i + 1) & mask) {
        }
    }
    t.slots[i] = LocalTable::Slot{p.key, p.hit, p.d2};
    ++t.used;
    cache_.idBestHit_[p.hit] = p.hit;
    cache_.hitId_[p.hit] = p.hit;
}

void HitCache::finish() {
    // Merge the threads' tables: one group per key, the best candidate over all of them.
    std::size_t total = 0;
    for (const std::unique_ptr<LocalTable>& t : tables_)
        if (t) total += t->used;
    KeyTable<GroupEntry> merged;
    merged.clear(total);
    for (const std::unique_ptr<LocalTable>& t : tables_) {
        if (!t) continue;
        for (const LocalTable::Slot& s : t->slots) {
            if (s.key == 0) continue;
            const std::uint64_t best = (std::uint64_t(s.d2) << 32) | idBestHit_[s.id];
            std::size_t slot = 0;
            GroupEntry* g = merged.find(s.key, &slot);
            if (!g) g = &merged.insert(s.key, slot, GroupEntry{s.key, best});
            else g->best = std::min(g->best, best);
            idGroup_[s.id] = std::uint32_t(g - merged.entries().data());
        }
    }
    representatives_.resize(merged.entries().size());
    for (std::size_t g = 0; g < representatives_.size(); ++g)
        representatives_[g] = std::size_t(merged.entries()[g].best & 0xFFFFFFFFu);
}

}  // namespace voxgi
