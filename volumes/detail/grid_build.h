// Internal: voxel sums -> a compact level (volumes/grid_build.cpp).
#pragma once

#include "volumes/detail/accumulation.h"
#include "volumes/detail/geometry_grids.h"

namespace voxgi::detail {

// Finishes the sums into the level's topology and attribute arrays (the level is consumed).
LevelGrids buildLevelGrids(AccumLevel&& level, double voxelSize, BlockerFit fit);

}  // namespace voxgi::detail
