// The NanoVDB geometry volume back as OpenVDB grids, for .vdb dumps (vdb_print, pyopenvdb). It
// includes OpenVDB: include it from .cpp files only.
#pragma once

#include <string>

#include <openvdb/openvdb.h>

namespace voxgi {

struct NanoGeometry;

// `prefix` + "normal" (mean normal times consistency), "albedo" and, when present,
// "surface_offset" (m along the normal from the voxel's centre), in world space (voxel ijk
// covers [ijk, ijk + 1] * voxelSize).
openvdb::GridPtrVec nanoGeometryGrids(const NanoGeometry& geometry, const std::string& prefix);

}  // namespace voxgi
