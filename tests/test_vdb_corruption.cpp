// Small .vdb files of every value kind and codec voxgi may meet (float, vec3s, bool; none, zip,
// blosc, active-mask; floats saved as half; written as a file or as a stream), each corrupted one byte at a time: every copy is
// read or refused with an InputError, never a crash or another exception. Run under
// scripts/sanitize-tests.sh, an overflow inside OpenVDB's reads (it copies through the
// sanitizer's memcpy) fails the test too: OpenVDB 10.0 read a chunk marked "uncompressed"
// into its node's buffer before comparing sizes.
#include <gtest/gtest.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "scenes/errors.h"
#include "support/test_support.h"
#include "volumes/vdb_inspect.h"

namespace {

// Two leaves in different internal nodes, active and inactive values (so nodes store masks and
// inactive values), and one active tile.
template <typename GridT>
typename GridT::Ptr smallGrid(const typename GridT::ValueType& on, const typename GridT::ValueType& off) {
    auto grid = GridT::create(typename GridT::ValueType());
    auto acc = grid->getAccessor();
    for (int i = 0; i < 6; ++i) acc.setValue(openvdb::Coord(i, 2 * i, 1), on);
    acc.setValueOff(openvdb::Coord(3, 0, 1), off);
    acc.setValue(openvdb::Coord(-300, 40, 9), on);
    grid->tree().addTile(1, openvdb::Coord(512, 0, 0), on, true);
    grid->setName("g");
    return grid;
}

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

TEST(VdbCorruption, EveryCorruptedByteIsReadOrRefused) {
    openvdb::initialize();
    const std::string dir = voxgi::test::makeTempDir("vdb-corruption");
    struct Codec {
        const char* name;
        std::uint32_t flags;
    };
    const Codec codecs[] = {{"none", openvdb::io::COMPRESS_NONE},
                            {"zip", openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK},
                            {"blosc", openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK},
                            {"stream", openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK}};
    for (const Codec& codec : codecs) {
        for (int kind = 0; kind < 4; ++kind) {
            openvdb::GridBase::Ptr grid;
            if (kind == 0) grid = smallGrid<openvdb::FloatGrid>(1.5f, -2.0f);
            if (kind == 1) grid = smallGrid<openvdb::Vec3SGrid>(openvdb::Vec3s(1, 2, 3), openvdb::Vec3s(-1, 0, 0));
            if (kind == 2) grid = smallGrid<openvdb::BoolGrid>(true, true);
            if (kind == 3) {
                grid = smallGrid<openvdb::FloatGrid>(0.25f, 3.0f);
                grid->setSaveFloatAsHalf(true);
            }
            const std::string name = std::string(codec.name) + "-" + std::to_string(kind);
            const std::string path = dir + "/" + name + ".vdb";
            if (std::string(codec.name) == "stream") {
                // io::Stream's layout: no grid offsets, each grid right after its descriptor.
                std::ofstream out(path, std::ios::binary);
                openvdb::io::Stream stream(out);
                stream.setCompression(codec.flags);
                stream.write(openvdb::GridCPtrVec{grid});
            } else {
                openvdb::io::File file(path);
                file.setCompression(codec.flags);
                file.write(openvdb::GridCPtrVec{grid});
                file.close();
            }
            ASSERT_NO_THROW(voxgi::inspectVdbFile(path)) << name;
            const std::string bytes = readAll(path);
            int refused = 0, read = 0;
            // 500 bytes spread over the file past the magic number, each flipped: headers,
            // masks, chunk sizes and data (every byte of every file took 13 minutes).
            const std::size_t stride = std::max<std::size_t>(1, bytes.size() / 500);
            for (std::size_t at = 8; at < bytes.size(); at += stride) {
                std::string corrupt = bytes;
                corrupt[at] = char(corrupt[at] ^ 0xff);
                const std::string copy = dir + "/" + name + "-corrupt.vdb";
                voxgi::test::writeFile(copy, corrupt);
                try {
                    voxgi::inspectVdbFile(copy);
                    ++read;
                } catch (const voxgi::InputError&) {
                    ++refused;
                } catch (const std::exception& e) {
                    ADD_FAILURE() << name << " with byte " << at << " flipped: " << e.what();
                }
            }
            EXPECT_GT(refused, 0) << name;
            EXPECT_GT(read, 0) << name;  // flips in values and names leave a readable file
        }
    }
}

// OpenVDB reads a grid's leaf buffers where its topology ends, whatever the grid descriptor's
// block position says; a check that seeks to the stated block instead walks other bytes than
// OpenVDB reads (the fuzzer's finding: an 8e18-byte chunk allocated by bloscFromStream). A block
// position off the topology's end is refused.
TEST(VdbCorruption, ABlockPositionOffTheTopologysEndIsRefused) {
    openvdb::initialize();
    const std::string dir = voxgi::test::makeTempDir("vdb-block-position");
    const std::string path = dir + "/float-blosc.vdb";
    {
        openvdb::io::File file(path);
        file.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
        file.write(openvdb::GridCPtrVec{smallGrid<openvdb::FloatGrid>(1.5f, -2.0f)});
        file.close();
    }
    std::string bytes = readAll(path);
    // Header: magic, version, library version, offsets flag, UUID, an empty metadata table,
    // the grid count; then the descriptor: name, type, instance parent (length-prefixed), and
    // the grid, block and end positions.
    std::size_t at = 8 + 4 + 8 + 1 + 36 + 4 + 4;
    for (int text = 0; text < 3; ++text) {
        std::uint32_t length = 0;
        std::copy_n(bytes.data() + at, 4, reinterpret_cast<char*>(&length));
        at += 4 + length;
    }
    std::int64_t positions[3];
    std::copy_n(bytes.data() + at, sizeof positions, reinterpret_cast<char*>(positions));
    ASSERT_EQ(positions[2], std::int64_t(bytes.size()));  // the descriptor was found
    for (const std::int64_t shift : {-1, 1, 16}) {
        std::string moved = bytes;
        const std::int64_t block = positions[1] + shift;
        std::copy_n(reinterpret_cast<const char*>(&block), 8, moved.data() + at + 8);
        const std::string copy = dir + "/moved.vdb";
        voxgi::test::writeFile(copy, moved);
        try {
            voxgi::inspectVdbFile(copy);
            ADD_FAILURE() << "block position moved by " << shift << " was read";
        } catch (const voxgi::InputError& e) {
            EXPECT_NE(std::string(e.what()).find("block position"), std::string::npos) << e.what();
        }
    }
}

// Every regression seed the fuzzer found (tests/fuzz/corpus/vdb/regression-*.bin) is read or
// refused with an InputError. One states a blosc chunk of 4e15 bytes past a moved block
// position: OpenVDB allocates it unless the walk refuses the file first, which the ordinary
// build turns into an InputError (std::bad_alloc) and AddressSanitizer into an abort
// (scripts/sanitize-tests.sh runs this test).
TEST(VdbCorruption, FuzzerRegressionSeedsAreReadOrRefused) {
    openvdb::initialize();
    const std::string corpus = std::string(VOXGI_SOURCE_DIR) + "/tests/fuzz/corpus/vdb";
    int seeds = 0;
    for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
        if (entry.path().filename().string().rfind("regression-", 0) != 0) continue;
        ++seeds;
        try {
            voxgi::inspectVdbFile(entry.path().string());
        } catch (const voxgi::InputError&) {
        } catch (const std::exception& e) {
            ADD_FAILURE() << entry.path() << ": " << e.what();
        }
    }
    EXPECT_GE(seeds, 2);
}
