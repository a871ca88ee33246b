// Internal: the mesh as OpenVDB point/triangle arrays and the optional signed distance grid.
#pragma once

#include <vector>

#include <openvdb/openvdb.h>

#include "volumes/geometry_volume.h"

namespace voxgi::detail {

struct MeshArrays {
    std::vector<openvdb::Vec3s> points;      // world space, all meshes concatenated
    std::vector<openvdb::Vec3I> triangles;   // only triangles with finite vertices and valid indices
};

MeshArrays collectMeshArrays(const Scene& scene);

// Narrow-band level set (OpenVDB meshToLevelSet) at level-0 voxel size; meaningful for
// watertight meshes only (open meshes get an arbitrary inside/outside).
openvdb::FloatGrid::Ptr buildSdf(const Scene& scene, const VoxelizeSettings& settings);

}  // namespace voxgi::detail
