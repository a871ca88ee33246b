// Internal: the triangle pass that fills level 0 (volumes/voxelizer.cpp).
#pragma once

#include "volumes/detail/accumulation.h"
#include "volumes/geometry_volume.h"

namespace voxgi::detail {

// Skips and counts bad triangles; throws InputError when the voxel estimate exceeds maxVoxels.
AccumLevel voxelizeTriangles(const Scene& scene, const VoxelizeSettings& settings, VoxelizeStats& stats);

}  // namespace voxgi::detail
