// Writing .vdb files, for the sources that build OpenVDB grids themselves (the geometry volume,
// the LPV and DDGI dumps). It includes OpenVDB: include it from .cpp files only.
#pragma once

#include <string>

#include <openvdb/openvdb.h>

namespace voxgi {

// Writes `grids` (and the file's `meta`) through writeFileAtomically: all or nothing, failures
// an InputError naming the file.
void writeVdbFile(const std::string& path, const openvdb::GridPtrVec& grids,
                  const openvdb::MetaMap& meta = openvdb::MetaMap());

}  // namespace voxgi
