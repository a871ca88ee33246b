#include "volumes/detail/vdb_tree_walk.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace voxgi::detail {

namespace {

// io/Compression.h: the grid's compression flags and a node's compression metadata byte.
constexpr std::uint32_t kZip = 0x1, kActiveMask = 0x2, kBlosc = 0x4;
enum : std::int8_t {
    kNoMaskOneInactive = 2,  // one inactive value stored
    kMaskNoInactive = 3,     // a selection mask stored
    kMaskOneInactive = 4,    // a selection mask and one inactive value
    kMaskTwoInactive = 5,    // a selection mask and two inactive values
    kAllValues = 6           // every value stored, active or not
};

using NodeMask = std::vector<std::uint64_t>;

std::uint64_t countOn(const NodeMask& m) {
    std::uint64_t n = 0;
    for (std::uint64_t word : m) n += std::uint64_t(__builtin_popcountll(word));
    return n;
}

std::uint32_t littleEndian32(const unsigned char* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

class TreeWalk {
public:
    TreeWalk(VdbFields& f, const VdbTreeLayout& tree) : f_(f), tree_(tree) {}

    void topology(std::uint32_t tiles, std::uint32_t children) {
        f_.skip(std::uint64_t(tiles) * (12 + tree_.valueBytes + 1), "root tiles");
        std::array<std::int32_t, 3> previous{};
        for (std::uint32_t i = 0; i < children; ++i) {
            std::array<std::int32_t, 3> origin{};
            f_.bytes(origin.data(), sizeof origin, "root child origin");
            // OpenVDB reads the leaf buffers in its table's order (by origin): children out of
            // that order, or repeated, would pair the buffers with other leaves' masks.
            if (i > 0 && !(previous < origin)) f_.fail("root children out of order");
            previous = origin;
            internalNode(32768);
        }
    }

    // OpenVDB reads the buffers where the topology ends whatever the grid's block position
    // says, so the walk does too (the caller has checked that both agree).
    void buffers(std::uint64_t end) {
        for (std::size_t leaf = 0; leaf < leafMasks_.size(); leaf += 8) {
            if (tree_.leaves == VdbTreeLayout::Leaves::Bool) {
                f_.skip(64 + 12 + 64, "bool leaf buffer");  // value mask, origin, value bits
            } else if (tree_.leaves == VdbTreeLayout::Leaves::Mask) {
                f_.skip(64 + 12, "mask leaf buffer");  // value bits, origin
            } else {
                // OpenVDB counts the stored values with the buffer's mask or the topology's
                // (when the stream is seekable): in a valid file they are the same.
                const NodeMask active = mask(512, "leaf value mask");
                if (!std::equal(active.begin(), active.end(), leafMasks_.begin() + std::ptrdiff_t(leaf)))
                    f_.fail("leaf value mask differs from the tree topology's");
                values(512, countOn(active));
            }
        }
        if (f_.position() > end) f_.fail("leaf buffers run past the grid's end");
    }

private:
    NodeMask mask(std::uint64_t bits, const char* what) {
        NodeMask m(bits / 64);
        f_.bytes(m.data(), bits / 8, what);
        return m;
    }

    // An internal node of `size` values (32^3 under the root, 16^3 below): child and value
    // masks, its values, then its children (leaves of 8^3 below the 16^3 nodes).
    void internalNode(std::uint64_t size) {
        const NodeMask children = mask(size, "node child mask");
        const NodeMask active = mask(size, "node value mask");
        values(size, countOn(active));
        for (std::uint64_t word : children)
            for (; word != 0; word &= word - 1) {
                if (size == 32768) internalNode(4096);
                else {
                    const NodeMask leaf = mask(512, "leaf mask");
                    leafMasks_.insert(leafMasks_.end(), leaf.begin(), leaf.end());
                }
            }
    }

    // readCompressedValues: a metadata byte, up to two inactive values, a selection mask, then
    // the stored values (only the active ones under active-mask compression).
    void values(std::uint64_t size, std::uint64_t active) {
        const std::int8_t metadata = f_.value<std::int8_t>("node compression metadata");
        if (metadata < 0 || metadata > kAllValues) f_.fail("node compression metadata " + std::to_string(metadata));
        const bool oneInactive =
            metadata == kNoMaskOneInactive || metadata == kMaskOneInactive || metadata == kMaskTwoInactive;
        if (oneInactive) f_.skip(tree_.valueBytes, "inactive value");
        if (metadata == kMaskTwoInactive) f_.skip(tree_.valueBytes, "second inactive value");
        if (metadata >= kMaskNoInactive && metadata <= kMaskTwoInactive) f_.skip(size / 8, "selection mask");
        const std::uint64_t stored = (tree_.compression & kActiveMask) && metadata != kAllValues ? active : size;
        // Values saved as half floats go through HalfReader, which reads nothing at all for none.
        if (stored == 0 && tree_.chunkValueBytes != tree_.valueBytes) return;
        chunk(stored * tree_.chunkValueBytes);
    }

    // readData: raw values, or a compressed chunk: its signed size (negative: stored raw), then
    // its bytes.
    void chunk(std::uint64_t bytes) {
        if (!(tree_.compression & (kZip | kBlosc))) {
            f_.skip(bytes, "node values");
            return;
        }
        const std::int64_t size = f_.value<std::int64_t>("chunk size");
        if (size <= 0) {
            const std::uint64_t raw = std::uint64_t(0) - std::uint64_t(size);
            if (raw != bytes)
                f_.fail("uncompressed chunk of " + std::to_string(raw) + " bytes for " + std::to_string(bytes));
            f_.skip(raw, "uncompressed chunk");
            return;
        }
        if (std::uint64_t(size) > f_.left()) f_.fail("chunk of " + std::to_string(size) + " bytes runs past the end of the file");
        if (!(tree_.compression & kBlosc)) {
            f_.skip(std::uint64_t(size), "zip chunk");
            return;
        }
        // blosc decodes the byte count its header states and reads the compressed bytes it
        // states, trusting both.
        unsigned char header[16];
        if (size < 16) f_.fail("blosc chunk of " + std::to_string(size) + " bytes");
        f_.bytes(header, sizeof header, "blosc chunk header");
        const std::uint32_t decoded = littleEndian32(header + 4), encoded = littleEndian32(header + 12);
        if (decoded != bytes || encoded > std::uint64_t(size))
            f_.fail("blosc chunk of " + std::to_string(size) + " bytes claims " + std::to_string(encoded) + " encoding " +
                    std::to_string(decoded) + " for " + std::to_string(bytes));
        f_.skip(std::uint64_t(size) - 16, "blosc chunk");
    }

    VdbFields& f_;
    const VdbTreeLayout& tree_;
    std::vector<std::uint64_t> leafMasks_;  // 8 words per leaf, in the order of the buffers
};

}  // namespace

void walkVdbTree(VdbFields& f, const VdbTreeLayout& tree, std::uint32_t tiles, std::uint32_t children,
                 std::uint64_t block, std::uint64_t end) {
    TreeWalk walk(f, tree);
    walk.topology(tiles, children);
    // A streamed file (block past the file's end) has no block position to agree with.
    if (block <= f.size() && f.position() != block)
        f.fail("tree topology ends at byte " + std::to_string(f.position()) + ", not at the grid's block position " +
               std::to_string(block));
    walk.buffers(end);
}

}  // namespace voxgi::detail
