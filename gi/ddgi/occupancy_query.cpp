#include "gi/ddgi/occupancy_query.h"

#include <algorithm>
#include <cmath>

#include "gi/raytrace/ray_tracer.h"
#include "shaders/shared/material.h"
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
    VoxelizeSettings settings;
    settings.voxelSize = field.smallestSpacing() / float(field.desc().traceVoxels);
    const float h = settings.voxelSize, reach = 0.5f * std::sqrt(3.0f) * h;
    const Scene& scene = tracer.scene();
    const SurfaceProbe probe = [&tracer, &scene, h, reach](glm::vec3 centre, glm::vec3 n) {
        VoxelSurface s;
        // The nearest surface along the mean normal, either way, within half the voxel's
        // diagonal: shading then happens on the surface, not where the ray entered the voxel
        // (up to a diagonal before it, which put the Cornell box's ceiling below its light).
        const RayHit up = tracer.intersect(centre, n, 0.0f, reach), down = tracer.intersect(centre, -n, 0.0f, reach);
        if (up.hit && (!down.hit || up.t <= down.t)) s.offset = up.t;
        else if (down.hit) s.offset = -down.t;
        // What rays arriving along -n see in this voxel: five rays from the normal side (the
        // centre's and four a quarter voxel across), front faces inside the voxel only, their
        // diffuse albedo averaged over a voxel-wide footprint.
        const glm::vec3 t = glm::normalize(std::abs(n.x) < 0.9f ? glm::cross(n, glm::vec3(1, 0, 0)) : glm::cross(n, glm::vec3(0, 1, 0)));
        const glm::vec3 b = glm::cross(n, t);
        const glm::vec2 across[5] = {{0, 0}, {0.25f, 0.25f}, {-0.25f, 0.25f}, {0.25f, -0.25f}, {-0.25f, -0.25f}};
        glm::vec3 sum(0.0f);
        int seen = 0;
        for (const glm::vec2& a : across) {
            const glm::vec3 origin = centre + reach * n + h * (a.x * t + a.y * b);
            const RayHit hit = tracer.intersect(origin, -n, 0.0f, 2.0f * reach);
            if (!hit.hit || !(glm::dot(hit.geometricNormal, n) > 0.0f)) continue;
            if (glm::any(glm::greaterThan(glm::abs(hit.position - centre), glm::vec3(0.5f * h)))) continue;
            const Material& m = scene.materials[hit.material];
            sum += shading::diffuseAlbedo(tracer.albedoInCone(hit, -n, h / std::max(hit.t, 1e-3f * h)), m.metallic,
                                          m.specular, m.transmission);
            ++seen;
        }
        if (seen > 0) {
            s.albedo = sum / float(seen);
            s.albedoSeen = true;
        }
        return s;
    };
    return makeNanoGeometry(voxelizeScene(scene, settings), 0, probe);
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
