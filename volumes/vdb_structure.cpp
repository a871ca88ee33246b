#include "volumes/vdb_structure.h"

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "scenes/errors.h"
#include "volumes/detail/vdb_fields.h"
#include "volumes/detail/vdb_tree_walk.h"

namespace voxgi {

namespace {

// File format versions (OpenVDB's version.h) where the layout this check reads changed.
constexpr std::uint32_t kTextUuidVersion = 218;           // oldest layout read: a text UUID (2013)
constexpr std::uint32_t kGridInstancingVersion = 216;     // descriptors name an instance parent
constexpr std::uint32_t kNewTransformVersion = 219;       // transforms start with their type name
constexpr std::uint32_t kSelectiveCompressionVersion = 220;  // no file-wide compression byte
constexpr std::uint32_t kGridCompressionVersion = 222;    // per-grid compression flags

// The metadata types OpenVDB registers with a fixed size, and that size.
const std::map<std::string, std::uint32_t> kFixedMetadataSizes = {
    {"bool", 1},    {"int32", 4},   {"int64", 8},   {"float", 4},   {"double", 8},  {"vec2i", 8},
    {"vec2s", 8},   {"vec2d", 16},  {"vec3i", 12},  {"vec3s", 12},  {"vec3d", 24},  {"vec4i", 16},
    {"vec4s", 16},  {"vec4d", 32},  {"mat4s", 64},  {"mat4d", 128}};

// A metadata table (OpenVDB's MetaMap): a count, then per item a name, a type name and the
// value's byte count and bytes. OpenVDB allocates each string at the length the file states
// and loops over the count, so both are bounded by the bytes left. Names may not be empty.
void checkMetadata(detail::VdbFields& f, const std::string& what) {
    const std::int32_t count = f.value<std::int32_t>((what + " count").c_str());
    if (count < 0 || std::uint64_t(count) * 12 > f.left()) f.fail(what + " count " + std::to_string(count));
    for (std::int32_t i = 0; i < count; ++i) {
        if (f.text("metadata name").empty()) f.fail(what + " item " + std::to_string(i) + " has an empty name");
        const std::string type = f.text("metadata type name");
        const std::uint32_t size = f.value<std::uint32_t>("metadata size");
        // OpenVDB reads a registered fixed-size type at its own size whatever the file says, and
        // a mismatch sends every later read into the middle of a value.
        const auto fixed = kFixedMetadataSizes.find(type);
        if (fixed != kFixedMetadataSizes.end() && fixed->second != size)
            f.fail(what + " item " + std::to_string(i) + " of type " + type + " has " + std::to_string(size) +
                   " bytes, not " + std::to_string(fixed->second));
        f.skip(size, "metadata value");
    }
}

// Bytes of a map's data after its type name (OpenVDB's Maps.h: each reads Vec3d and Mat4d
// members); a type not listed (the frustum map) ends the check of that grid.
const std::map<std::string, std::uint64_t> kMapBytes = {
    {"AffineMap", 128},           {"UnitaryMap", 128},        {"ScaleMap", 120}, {"UniformScaleMap", 120},
    {"TranslationMap", 24},       {"ScaleTranslateMap", 144}, {"UniformScaleTranslateMap", 144}};

// A grid type such as "Tree_float_5_4_3" (with "_HalfFloat" when floats are saved as halves)
// as the walk sees it; valueBytes 0 for a value type not listed. Only trees of 5-4-3 nodes of
// plain value types are walked below the root (point and string grids store other buffers).
struct TreeType {
    std::uint64_t valueBytes = 0;
    bool walkable = false;
    detail::VdbTreeLayout layout;
};

TreeType treeType(const std::string& gridType) {
    struct Known {
        std::uint64_t bytes, halfBytes;
        detail::VdbTreeLayout::Leaves leaves;
        bool walkable;
    };
    using L = detail::VdbTreeLayout::Leaves;
    static const std::map<std::string, Known> kTypes = {
        {"bool", {1, 1, L::Bool, true}},        {"mask", {1, 1, L::Mask, true}},
        {"float", {4, 2, L::Values, true}},     {"double", {8, 2, L::Values, true}},
        {"int32", {4, 4, L::Values, true}},     {"int64", {8, 8, L::Values, true}},
        {"vec3s", {12, 6, L::Values, true}},    {"vec3d", {24, 6, L::Values, true}},
        {"vec3i", {12, 12, L::Values, true}},   {"ptidx32", {4, 4, L::Values, false}},
        {"ptdataidx32", {4, 4, L::Values, false}}};
    TreeType t;
    if (gridType.rfind("Tree_", 0) != 0) return t;
    const std::size_t end = gridType.find('_', 5);
    if (end == std::string::npos) return t;
    const auto it = kTypes.find(gridType.substr(5, end - 5));
    if (it == kTypes.end()) return t;
    const std::string nodes = gridType.substr(end);
    const bool half = nodes == "_5_4_3_HalfFloat";
    t.valueBytes = it->second.bytes;
    t.walkable = it->second.walkable && (nodes == "_5_4_3" || half);
    t.layout.valueBytes = it->second.bytes;
    t.layout.chunkValueBytes = half ? it->second.halfBytes : it->second.bytes;
    t.layout.leaves = it->second.leaves;
    return t;
}

// A grid from its position to the end of its leaf buffers: compression flags, metadata,
// transform, then the root node's tile and child counts, which OpenVDB loops over (reading
// nothing once the file ends: 2e9 tiles took 14 s) and which must fit before the buffers. Below
// the root, detail::walkVdbTree checks every node's masks and chunk sizes. In a streamed file
// (no grid offsets) `block` is kBuffersFollow: the buffers follow the topology. True when the
// walk reached the grid's end, so that a streamed file's next grid starts there.
constexpr std::uint64_t kBuffersFollow = ~std::uint64_t(0);

bool checkGrid(detail::VdbFields& f, std::uint32_t version, const std::string& type, bool instance, std::uint64_t block,
               std::uint64_t end) {
    TreeType tree = treeType(type);
    if (version >= kGridCompressionVersion) tree.layout.compression = f.value<std::uint32_t>("grid compression flags");
    checkMetadata(f, "grid metadata");
    if (version < kNewTransformVersion) return false;
    const std::string map = f.text("grid transform type");
    const auto mapBytes = kMapBytes.find(map);
    if (mapBytes == kMapBytes.end()) return false;
    f.skip(mapBytes->second, "grid transform");
    if (instance) return true;  // an instance shares its parent's tree
    if (tree.valueBytes == 0) return false;
    f.value<std::int32_t>("tree buffer count");
    f.skip(tree.valueBytes, "tree background value");
    const std::uint32_t tiles = f.value<std::uint32_t>("root tile count"),
                        children = f.value<std::uint32_t>("root child count");
    const std::uint64_t needed = std::uint64_t(tiles) * (12 + tree.valueBytes + 1) + std::uint64_t(children) * 12;
    const std::uint64_t limit = block == kBuffersFollow ? f.size() : block;
    if (f.position() > limit || needed > limit - f.position())
        f.fail("root node of " + std::to_string(tiles) + " tiles and " + std::to_string(children) +
               " children does not fit before the grid's buffers");
    if (!tree.walkable || version < kGridCompressionVersion) return false;
    detail::walkVdbTree(f, tree.layout, tiles, children, block == kBuffersFollow ? f.size() + 1 : block, end);
    return true;
}

bool isUuid(const char* s) {
    for (int i = 0; i < 36; ++i) {
        const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
        if (dash ? s[i] != '-' : !std::isxdigit(static_cast<unsigned char>(s[i]))) return false;
    }
    return true;
}

}  // namespace

void checkVdbStructure(const std::string& path) {
    detail::VdbFields f(path);
    unsigned char magic[8] = {};
    const unsigned char expected[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};  // 0x56444220, "VDB "
    if (f.left() < 8) throw InputError(path + ": not a .vdb file (no OpenVDB header)");
    f.bytes(magic, 8, "magic number");
    if (std::memcmp(magic, expected, 8) != 0) throw InputError(path + ": not a .vdb file (no OpenVDB header)");
    const std::uint32_t version = f.value<std::uint32_t>("file version");
    if (version < kTextUuidVersion)
        f.fail("file format version " + std::to_string(version) + " predates OpenVDB 1.0; voxgi reads " +
               std::to_string(kTextUuidVersion) + " and later");
    f.value<std::uint32_t>("library major version");
    f.value<std::uint32_t>("library minor version");
    const char hasOffsets = f.value<char>("grid offsets flag");
    if (version < kSelectiveCompressionVersion) f.value<char>("file compression flag");
    char uuid[36];
    f.bytes(uuid, 36, "file UUID");
    if (!isUuid(uuid)) f.fail("corrupt file UUID");
    checkMetadata(f, "file metadata");
    const std::int32_t grids = f.value<std::int32_t>("grid count");
    if (grids < 0 || std::uint64_t(grids) * 36 > f.left()) f.fail("grid count " + std::to_string(grids));
    for (std::int32_t i = 0; i < grids; ++i) {
        f.text("grid name");
        const std::string type = f.text("grid type");
        const bool instance = version >= kGridInstancingVersion && !f.text("grid instance parent").empty();
        const std::int64_t grid = f.value<std::int64_t>("grid position"), block = f.value<std::int64_t>("block position"),
                           end = f.value<std::int64_t>("grid end position");
        if (!hasOffsets) {
            // A streamed file: each grid follows its descriptor, and OpenVDB reads them all when
            // it opens the file. A grid the check cannot walk ends the check.
            if (!checkGrid(f, version, type, instance, kBuffersFollow, f.size())) return;
            continue;
        }
        if (!(std::uint64_t(grid) == f.position() && grid <= block && block <= end && std::uint64_t(end) <= f.size()))
            f.fail("grid " + std::to_string(i) + " offsets " + std::to_string(grid) + ", " + std::to_string(block) + ", " +
                   std::to_string(end) + " do not fit the file");
        checkGrid(f, version, type, instance, std::uint64_t(block), std::uint64_t(end));
        f.seek(std::uint64_t(end), "grid end position");
    }
}

}  // namespace voxgi
