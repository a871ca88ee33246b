#include "gi/ddgi/occupancy_query.h"

#include "volumes/geometry_volume.h"

namespace voxgi {

std::shared_ptr<const SparseGeometryVolume> voxelizeForProbes(const Scene& scene, const ProbeVolume& volume) {
    VoxelizeSettings settings;
    settings.voxelSize = 0.25f * volume.minSpacing();
    settings.levels = 2;
    return std::make_shared<const SparseGeometryVolume>(voxelizeScene(scene, settings));
}

GeometryQuery occupancyQuery(std::shared_ptr<const SparseGeometryVolume> voxels, const ProbeVolume& volume) {
    GeometryQuery query;
    const float far = 4.0f * volume.cellDiagonal();
    const glm::vec3 reach = 0.999f * volume.spacing;
    query.distanceToGeometry = [voxels, far, reach](glm::vec3 p) {
        // Level 1 voxels are half a cell: the block within one cell of p on every axis, the
        // same neighbourhood the fixed rays test.
        const int level = voxels->levelCount() - 1;
        glm::ivec3 lo = voxels->voxelAt(p - reach, level), hi = voxels->voxelAt(p + reach, level);
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x)
                    if (voxels->occupied(glm::ivec3(x, y, z), level)) return 0.0f;
        return far;
    };
    return query;
}

}  // namespace voxgi
