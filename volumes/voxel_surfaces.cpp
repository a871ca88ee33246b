#include "volumes/voxel_surfaces.h"

#include "volumes/detail/geometry_grids.h"

namespace voxgi {

void forEachVoxelSurface(const SparseGeometryVolume& volume, int level, const IndexBox& box,
                         const std::function<void(const VoxelSurfaceArea&)>& visit) {
    const BlockerFit fit = volume.grids().blockerFit;
    for (int z = box.min.z; z <= box.max.z; ++z)
        for (int y = box.min.y; y <= box.max.y; ++y)
            for (int x = box.min.x; x <= box.max.x; ++x) {
                const glm::ivec3 v(x, y, z);
                if (!volume.occupied(v, level)) continue;
                VoxelSurfaceArea s;
                s.voxel = v;
                s.vectorCoverage = volume.normal(v, level);
                s.coverage = coverageFromBlocker(volume.blockerSH(v, level)[0], s.vectorCoverage, fit);
                if (!(s.coverage > 0.0f)) continue;
                s.albedo = volume.albedo(v, level);
                s.projectedCoverage = volume.projectedCoverage(v, level);
                visit(s);
            }
}

}  // namespace voxgi
