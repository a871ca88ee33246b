// OpenVDB as an independent oracle: the voxelizer's occupancy against the surface band that
// OpenVDB's meshToVolume computes (unsigned distance + closest-triangle plane test) on the same
// mesh at the same voxel size.
#include <cstdio>
#include <set>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "scenes/primitives.h"
#include "scenes/scene_loader.h"
#include "support/test_support.h"
#include "volumes/geometry_volume.h"
#include "volumes/openvdb_reference.h"

using namespace voxgi;

namespace {

using Key = std::tuple<int, int, int>;

double occupancyIoU(const Scene& scene, float voxelSize, std::size_t* sizes = nullptr) {
    VoxelizeSettings settings;
    settings.voxelSize = voxelSize;
    SparseGeometryVolume volume = voxelizeScene(scene, settings);
    std::set<Key> oracle;
    for (const glm::ivec3& v : meshToVolumeSurfaceVoxels(scene, voxelSize)) oracle.insert({v.x, v.y, v.z});
    std::size_t both = 0, ours = 0;
    IndexBox box = volume.indexBounds();
    for (int z = box.min.z; z <= box.max.z; ++z)
        for (int y = box.min.y; y <= box.max.y; ++y)
            for (int x = box.min.x; x <= box.max.x; ++x)
                if (volume.occupied({x, y, z})) {
                    ++ours;
                    both += oracle.count({x, y, z});
                }
    std::printf("IoU %.4f: voxgi %zu voxels, meshToVolume band %zu, both %zu\n",
                double(both) / double(ours + oracle.size() - both), ours, oracle.size(), both);
    if (sizes) {
        sizes[0] = ours;
        sizes[1] = oracle.size();
    }
    return double(both) / double(ours + oracle.size() - both);
}

// A closed mesh with curved, tilted and sharp parts: a sphere and a rotated box, overlapping.
Scene generatedClosedMesh() {
    Scene scene;
    scene.materials.push_back(Material{});
    scene.meshes.push_back(makeSphere(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.03f, 0.11f, -0.02f)),
                                                 glm::vec3(0.07f)), 0, 48));
    glm::mat4 box = glm::translate(glm::mat4(1.0f), glm::vec3(-0.02f, 0.05f, 0.01f));
    box = glm::rotate(box, 0.6f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
    scene.meshes.push_back(makeBox(glm::scale(box, glm::vec3(0.09f, 0.05f, 0.12f)), 0));
    return scene;
}

}  // namespace

TEST(VoxelizeOracle, StanfordBunnyMatchesMeshToVolumeBand) {
    std::string dir = test::sharedScenesDir();
    Scene scene = dir.empty() ? generatedClosedMesh()
                              : sceneFromMeshFile(dir + "/stanford-bunny/bun_zipper_res2.ply");
    Bounds b = scene.bounds();
    glm::vec3 e = b.extent();
    float voxel = std::max(e.x, std::max(e.y, e.z)) / 64.0f;
    std::size_t sizes[2];
    double iou = occupancyIoU(scene, voxel, sizes);
    EXPECT_GE(iou, 0.95) << "voxgi " << sizes[0] << " voxels, meshToVolume band " << sizes[1];
    EXPECT_GT(sizes[0], 1000u);
}

TEST(VoxelizeOracle, GeneratedClosedMeshMatchesMeshToVolumeBand) {
    Scene scene = generatedClosedMesh();
    std::size_t sizes[2];
    double iou = occupancyIoU(scene, 0.004f, sizes);
    EXPECT_GE(iou, 0.95) << "voxgi " << sizes[0] << " voxels, meshToVolume band " << sizes[1];
}
