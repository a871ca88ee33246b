// Probe rays cast on the GPU through the NanoVDB geometry volume (volume_rays.comp) against
// Embree on the triangles: the same rays must agree on hit or miss, on which side was hit, on
// the distance to within the voxel the volume sees, and on the surface's normal and albedo.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "gi/ddgi/probe_rays.h"
#include "gi/ddgi/volume_trace_gpu.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/sampling/sequences.h"
#include "scenes/errors.h"
#include "scenes/memory_limit.h"
#include "scenes/scene_loader.h"
#include "support/test_support.h"
#include "test_ddgi_scenes.h"
#include "volumes/geometry_volume.h"
#include "volumes/nano_geometry.h"

using namespace voxgi;

namespace {


float percentile(std::vector<float> v, float q) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0f : v[std::size_t(q * float(v.size() - 1))];
}

struct Agreement {
    int rays = 0, bothHit = 0, hitMismatch = 0, sideMismatch = 0, farther = 0;
    std::vector<float> distanceError;  // (embree - volume) / voxel along the ray, front hits of both
    std::vector<float> depthError;     // the same across the surface (along its normal)
    double normalDot = 0.0, albedoError = 0.0;
    int frontHits = 0;
};

// 4 x 4 x 4 probes spread inside `box` shoot 64 spherical Fibonacci rays each.
Agreement compare(const Scene& scene, const Bounds& box, float voxelSize) {
    VoxelizeSettings settings;
    settings.voxelSize = voxelSize;
    const SparseGeometryVolume volume = voxelizeScene(scene, settings);
    const NanoGeometry nano = makeNanoGeometry(volume);
    // Voxels a surface only touches (on their face) are dropped: they hold no surface.
    EXPECT_LE(nano.activeVoxels, volume.activeVoxelCount());
    EXPECT_GT(nano.activeVoxels, volume.activeVoxelCount() / 2);
    RayTracer tracer(scene);
    std::vector<VolumeRay> rays;
    for (int i = 0; i < 64; ++i) {
        const glm::vec3 f = (glm::vec3(i % 4, i / 4 % 4, i / 16) + 0.5f) / 4.0f;
        const glm::vec3 origin = box.min + f * box.extent();
        for (int r = 0; r < 64; ++r)
            rays.push_back({origin, 1e30f, sphericalFibonacci(r, 64), 0.0f});
    }
    VolumeTracerGl gpu(nano);
    const std::vector<VolumeHit> hits = gpu.trace(rays, kMissDistance);
    Agreement a;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        ++a.rays;
        const RayHit e = tracer.intersect(rays[i].origin, rays[i].direction);
        const bool volumeHit = hits[i].distance < kMissDistance;
        if (e.hit != volumeHit) {
            ++a.hitMismatch;
            continue;
        }
        if (!e.hit) continue;
        ++a.bothHit;
        if (e.frontFace != (hits[i].distance >= 0.0f)) {
            if (std::getenv("VOXGI_DEBUG_TRACE") && a.sideMismatch < 12)
                std::printf("side: p %.3f %.3f %.3f n %.2f %.2f %.2f front %d t %.3f vol t %.3f\n", e.position.x,
                            e.position.y, e.position.z, e.geometricNormal.x, e.geometricNormal.y, e.geometricNormal.z,
                            int(e.frontFace), e.t, hits[i].distance);
            ++a.sideMismatch;
            continue;
        }
        if (!e.frontFace) continue;
        ++a.frontHits;
        // The voxel is entered before the surface inside it is reached.
        if (hits[i].distance > e.t + 1e-4f) ++a.farther;
        a.distanceError.push_back((e.t - hits[i].distance) / voxelSize);
        a.depthError.push_back(std::abs(glm::dot(rays[i].direction, e.geometricNormal)) * a.distanceError.back());
        a.normalDot += glm::dot(hits[i].normal, e.geometricNormal);
        const glm::vec3 d = glm::abs(hits[i].albedo - tracer.albedoAt(e));
        a.albedoError += (d.x + d.y + d.z) / 3.0;
    }
    std::printf("%d rays: %d hit/miss and %d side mismatches, %d front hits; along the ray (voxels) median %.2f, "
                "95%% %.2f, max %.2f; across the surface 95%% %.2f, max %.2f; normal dot %.3f; albedo error %.4f\n",
                a.rays, a.hitMismatch, a.sideMismatch, a.frontHits, percentile(a.distanceError, 0.5f),
                percentile(a.distanceError, 0.95f), percentile(a.distanceError, 1.0f), percentile(a.depthError, 0.95f),
                percentile(a.depthError, 1.0f), a.normalDot / std::max(1, a.frontHits),
                a.albedoError / std::max(1, a.frontHits));
    return a;
}

}  // namespace

class DdgiVolumeTrace : public ::testing::Test {
protected:
    static void SetUpTestSuite() { test::useHeadlessContext(); }
};

TEST_F(DdgiVolumeTrace, CornellBoxRaysAgreeWithEmbree) {
    const Scene scene = loadSceneFile(std::string(VOXGI_SOURCE_DIR) + "/scenes/cornell-box.json");
    // Probes in the free space above the blocks (the blocks have no bottom faces: from inside
    // one, Embree reaches the floor where the volume stops at the block's voxels).
    Bounds box = scene.bounds();
    const glm::vec3 margin = 0.1f * box.extent();
    box.min += margin;
    box.max -= margin;
    box.min.y = 0.36f;
    const float voxel = glm::length(scene.bounds().extent()) / 128.0f;
    const Agreement a = compare(scene, box, voxel);
    ASSERT_GT(a.frontHits, 3000);
    // Grazing rays through an open side or along a wall may disagree on hit or side.
    EXPECT_LT(a.hitMismatch, a.rays / 50) << a.hitMismatch << " of " << a.rays;
    EXPECT_LT(a.sideMismatch, a.bothHit / 50) << a.sideMismatch << " of " << a.bothHit;
    EXPECT_EQ(a.farther, 0);
    // Entry into the surface's voxel: within a voxel diagonal across the surface.
    EXPECT_LT(percentile(a.distanceError, 0.5f), 1.5f);
    EXPECT_LT(percentile(a.depthError, 0.95f), 1.5f);
    EXPECT_GT(a.normalDot / a.frontHits, 0.97);
    EXPECT_LT(a.albedoError / a.frontHits, 0.03);
}

// Two rooms split by a wall half a voxel thick: the volume must not leak through it (the wall's
// voxels are occupied however thin it is), so no ray from one room ends in the other. The wall's
// two faces share its voxels, whose summed normals cancel: normals there are not checked.
TEST_F(DdgiVolumeTrace, AThinWallStopsRaysLikeTheTriangles) {
    const Scene scene = test::twoRooms(0.01f);
    Bounds room = scene.bounds();
    room.max.x = -0.1f;  // the lit room, x < 0
    room.min += glm::vec3(0.05f);
    room.max -= glm::vec3(0.05f);
    const Agreement a = compare(scene, room, 0.02f);
    ASSERT_GT(a.frontHits, 3000);
    EXPECT_EQ(a.hitMismatch, 0);
    EXPECT_LT(a.sideMismatch, a.bothHit / 50);
    EXPECT_EQ(a.farther, 0);
    EXPECT_LT(percentile(a.distanceError, 0.5f), 1.5f);
    EXPECT_LT(percentile(a.depthError, 0.95f), 1.5f);
}

// The NanoVDB volume's memory is estimated from the occupancy's nodes before it is built: the
// estimate covers the buffer, and a limit below it refuses the build with the volume named.
TEST_F(DdgiVolumeTrace, TheVolumesMemoryIsEstimatedBeforeItIsBuilt) {
    const Scene scene = loadSceneFile(std::string(VOXGI_SOURCE_DIR) + "/scenes/cornell-box.json");
    VoxelizeSettings settings;
    settings.voxelSize = glm::length(scene.bounds().extent()) / 128.0f;
    const SparseGeometryVolume volume = voxelizeScene(scene, settings);
    const SurfaceProbe none = [](glm::vec3, glm::vec3) { return VoxelSurface{}; };
    const double estimate = nanoGeometryBytes(volume, 0, true);
    const NanoGeometry nano = makeNanoGeometry(volume, 0, none);
    std::printf("estimate %.1f MiB, buffer %.1f MiB\n", estimate / 1048576.0, double(nano.bytes()) / 1048576.0);
    EXPECT_GE(estimate, double(nano.bytes()));
    // An upper bound: it counts the voxels a surface only touches, which the build then drops.
    EXPECT_LE(estimate, 6.0 * double(nano.bytes()));
    const std::uint64_t before = memoryLimit();
    setMemoryLimit(std::uint64_t(0.5 * estimate));
    try {
        makeNanoGeometry(volume, 0, none);
        ADD_FAILURE() << "not refused";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("the NanoVDB geometry volume"), std::string::npos) << e.what();
    }
    setMemoryLimit(before);
}
