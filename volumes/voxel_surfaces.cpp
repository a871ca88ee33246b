#include "volumes/voxel_surfaces.h"

#include "volumes/detail/geometry_grids.h"

namespace voxgi {

void forEachVoxelSurface(const SparseGeometryVolume& volume, int level, const IndexBox& box,
                         const std::function<void(const VoxelSurfaceArea&)>& visit) {
    const detail::GeometryGrids& grids = volume.grids();
    const detail::LevelGrids& l = grids.levels.at(std::size_t(level));
    for (int z = box.min.z; z <= box.max.z; ++z)
        for (int y = box.min.y; y <= box.max.y; ++y)
            for (int x = box.min.x; x <= box.max.x; ++x) {
                // One lookup for every attribute: -1 where the voxel is not occupied.
                const std::int64_t i = l.attributeIndex(openvdb::Coord(x, y, z));
                if (i < 0) continue;
                const glm::vec4& normalC0 = l.normalC0[std::size_t(i)];
                VoxelSurfaceArea s;
                s.voxel = glm::ivec3(x, y, z);
                s.vectorCoverage = glm::vec3(normalC0);
                s.coverage = coverageFromBlocker(normalC0.w, s.vectorCoverage, grids.blockerFit);
                if (!(s.coverage > 0.0f)) continue;
                s.albedo = detail::fromHalves(l.albedo[std::size_t(i)]);
                s.projectedCoverage = detail::fromHalves(l.projected[std::size_t(i)]);
                visit(s);
            }
}

}  // namespace voxgi
