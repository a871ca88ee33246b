// Blockers of static geometry from the voxelized scene (volumes/SparseGeometryVolume, cached as .vdb):
// voxel (i, j, k) of level L spans [i, i+1] h_L, so the light volume's cells coincide with the
// voxels and its geometry samples sit on voxel corners. Each occupied voxel's blocker is given
// to its 8 corners (merged with mergeBlockers), which makes a thin wall block at both of the
// corner planes around it: conservative against leaks.
#pragma once

#include <string>

#include "gi/lpv/light_volume.h"
#include "volumes/geometry_volume.h"

namespace voxgi {

// Fills `out` (placement already set, zeroed) from level `level` of the voxelized scene.
void staticBlockers(const SparseGeometryVolume& voxels, int level, BlockerVolume& out);

// The cache folder for voxelized scenes: $VOXGI_CACHE_DIR, else $HOME/.cache/voxgi, else /tmp.
std::string geometryCacheDir();

}  // namespace voxgi
