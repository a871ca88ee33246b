#include "volumes/detail/vdb_file.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "volumes/openvdb_file.h"
#include "volumes/openvdb_setup.h"

namespace voxgi::detail {

VdbFileContents readVdbFile(const std::string& path) {
    initializeOpenVdb();
    if (!std::filesystem::is_regular_file(path)) throw InputError(path + ": not found");
    {
        // Every .vdb starts with the 64-bit magic number 0x56444220 ("VDB " little-endian).
        std::ifstream in(path, std::ios::binary);
        unsigned char magic[8] = {};
        in.read(reinterpret_cast<char*>(magic), sizeof magic);
        const unsigned char expected[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};
        if (!in || !std::equal(magic, magic + 8, expected))
            throw InputError(path + ": not a .vdb file (no OpenVDB header)");
    }
    VdbFileContents contents;
    try {
        openvdb::io::File file(path);
        file.open(false);
        contents.meta = file.getMetadata();
        contents.grids = *file.getGrids();
        file.close();
    } catch (const std::exception& e) {
        throw InputError(path + ": not a readable .vdb file (" + std::string(e.what()) + ")");
    }
    return contents;
}

}  // namespace voxgi::detail

namespace voxgi {

void writeVdbFile(const std::string& path, const openvdb::GridPtrVec& grids, const openvdb::MetaMap& meta) {
    initializeOpenVdb();
    writeFileAtomically(path, [&](const std::string& temporary) {
        openvdb::io::File file(temporary);
        file.write(grids, meta);
        file.close();
    });
}

}  // namespace voxgi
