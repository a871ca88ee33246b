// The OpenVDB side of SparseGeometryVolume, for .cpp files only (never include from a public header).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <openvdb/openvdb.h>

#include "volumes/geometry_volume.h"

namespace voxgi::detail {

struct LevelGrids {
    double voxelSize = 0.0;
    openvdb::BoolGrid::Ptr occupancy;
    openvdb::Vec3fGrid::Ptr albedo;
    openvdb::Vec3fGrid::Ptr normal;
    std::array<openvdb::FloatGrid::Ptr, 4> blocker;  // SH coefficients c0..c3
};

struct GeometryGrids {
    std::vector<LevelGrids> levels;
    openvdb::FloatGrid::Ptr sdf;  // level 0, optional
    std::string sourceHash;
    BlockerFit blockerFit = BlockerFit::PlaneExact;
    VoxelizeStats stats;

    // Every grid, in the order files list them.
    openvdb::GridPtrVec all() const;
};

// Voxel (i, j, k) covers [i, i+1] * h in world space: centres at (i + 0.5) * h.
openvdb::math::Transform::Ptr voxelTransform(double voxelSize);

// Names, classes and voxgi metadata on every grid of `grids` (called after building or reading).
void annotateGrids(GeometryGrids& grids);

}  // namespace voxgi::detail
