// The surfaces inside each voxel, as area, area-weighted normal and area projected per axis: what
// a transport that stops light by projected area needs (gi/lpv/ordinates.h), read from the stored
// blocker c0, normal and projected coverage.
#pragma once

#include <functional>

#include <glm/glm.hpp>

#include "volumes/geometry_volume.h"

namespace voxgi {

struct VoxelSurfaceArea {
    glm::ivec3 voxel{0};
    float coverage = 0.0f;           // sum of clipped areas / voxel face area
    glm::vec3 vectorCoverage{0.0f};  // sum of clipped area x unit normal / voxel face area
    glm::vec3 projectedCoverage{0.0f};  // per axis, sum of clipped area x |normal component| / face area
    glm::vec3 albedo{0.0f};          // area-weighted diffuse albedo
};

// Calls `visit` for every voxel of `level` inside `box` (inclusive) that holds a surface (voxels
// a surface only touches on a face hold none).
void forEachVoxelSurface(const SparseGeometryVolume& volume, int level, const IndexBox& box,
                         const std::function<void(const VoxelSurfaceArea&)>& visit);

}  // namespace voxgi
