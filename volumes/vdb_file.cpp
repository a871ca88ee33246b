#include "volumes/detail/vdb_file.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "volumes/openvdb_file.h"
#include "volumes/openvdb_setup.h"
#include "volumes/vdb_structure.h"

namespace voxgi::detail {

VdbFileContents readVdbFile(const std::string& path) {
    initializeOpenVdb();
    if (!std::filesystem::is_regular_file(path)) throw InputError(path + ": not found");
    checkVdbStructure(path);
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
