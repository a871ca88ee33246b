#include <cmath>

#include <openvdb/tools/MeshToVolume.h>

#include "volumes/detail/geometry_grids.h"
#include "volumes/detail/sdf_fill.h"

namespace voxgi::detail {

MeshArrays collectMeshArrays(const Scene& scene) {
    MeshArrays arrays;
    for (const Mesh& mesh : scene.meshes) {
        const auto base = std::uint32_t(arrays.points.size());
        // Unusable vertices stay as placeholders (no kept triangle refers to them) so indices hold.
        for (const glm::vec3& p : mesh.positions) {
            bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
            arrays.points.push_back(finite ? openvdb::Vec3s(p.x, p.y, p.z) : openvdb::Vec3s(0.0f));
        }
        auto usable = [&](std::uint32_t i) {
            if (i >= mesh.positions.size()) return false;
            const glm::vec3& p = mesh.positions[i];
            return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
        };
        for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
            std::uint32_t a = mesh.indices[3 * f], b = mesh.indices[3 * f + 1], c = mesh.indices[3 * f + 2];
            if (usable(a) && usable(b) && usable(c)) arrays.triangles.emplace_back(base + a, base + b, base + c);
        }
    }
    return arrays;
}

openvdb::FloatGrid::Ptr buildSdf(const Scene& scene, const VoxelizeSettings& settings) {
    MeshArrays arrays = collectMeshArrays(scene);
    std::vector<openvdb::Vec4I> quads;
    auto xform = voxelTransform(settings.voxelSize);
    return openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, arrays.points, arrays.triangles, quads,
                                                              settings.sdfHalfWidth);
}

}  // namespace voxgi::detail
