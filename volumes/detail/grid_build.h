// Internal: voxel sums -> OpenVDB grids (volumes/grid_build.cpp).
#pragma once

#include "volumes/detail/accumulation.h"
#include "volumes/detail/geometry_grids.h"

namespace voxgi::detail {

// Finalizes the sums and moves the leaves into new grids (the level is consumed).
LevelGrids buildLevelGrids(AccumLevel&& level, double voxelSize, BlockerFit fit);

}  // namespace voxgi::detail
