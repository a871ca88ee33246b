// Internal: reading a whole .vdb file with every failure turned into an InputError.
#pragma once

#include <string>

#include <openvdb/openvdb.h>

namespace voxgi::detail {

struct VdbFileContents {
    openvdb::MetaMap::Ptr meta;
    openvdb::GridPtrVec grids;
};

// Checks existence and the OpenVDB magic number first (OpenVDB itself reads uninitialised
// bytes from empty or foreign files), then loads every grid.
VdbFileContents readVdbFile(const std::string& path);

}  // namespace voxgi::detail
