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
