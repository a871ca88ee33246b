#include "gi/ddgi/occupancy_query.h"

#include <algorithm>
#include <cmath>

#include "gi/raytrace/ray_tracer.h"
#include "volumes/geometry_volume.h"
#include "volumes/nano_geometry.h"

namespace voxgi {

std::shared_ptr<const SparseGeometryVolume> voxelizeForProbes(const Scene& scene, const ProbeVolume& volume) {
    VoxelizeSettings settings;
    settings.voxelSize = 0.25f * volume.minSpacing();
    settings.levels = 2;
    return std::make_shared<const SparseGeometryVolume>(voxelizeScene(scene, settings));
}

NanoGeometry voxelizeForTracing(const RayTracer& tracer, const ProbeField& field) {
    float spacing = field.volumes().front().minSpacing();
    for (const ProbeVolume& v : field.volumes()) spacing = std::min(spacing, v.minSpacing());
    VoxelizeSettings settings;
    settings.voxelSize = spacing / float(field.desc().traceVoxels);
    // The nearest surface along the voxel's mean normal, either way, within half its diagonal:
    // shading then happens on the surface, not where the ray entered the voxel (up to a
    // diagonal before it, which put the Cornell box's ceiling below its light).
    const float reach = 0.5f * std::sqrt(3.0f) * settings.voxelSize;
    const SurfaceOffset offset = [&tracer, reach](glm::vec3 centre, glm::vec3 n) {
        const RayHit up = tracer.intersect(centre, n, 0.0f, reach), down = tracer.intersect(centre, -n, 0.0f, reach);
        if (up.hit && (!down.hit || up.t <= down.t)) return up.t;
        return down.hit ? -down.t : 0.0f;
    };
    return makeNanoGeometry(voxelizeScene(tracer.scene(), settings), 0, offset);
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
