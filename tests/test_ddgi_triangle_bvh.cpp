// The triangle BVH (gi/raytrace/triangle_bvh.h) and its GPU traversal (shaders/common/
// triangle_bvh.glsl, run by shaders/ddgi/bvh_rays.comp) against Embree's own traversal of the
// same triangles: the same nearest triangle at the same distance, seen from the same side.
// (Any-hit traversal, the shadow rays', is checked through the shading in
// test_ddgi_volume_shade.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "gi/ddgi/probe_rays.h"
#include "gi/ddgi/volume_trace_gpu.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/raytrace/triangle_bvh.h"
#include "scenes/scene_loader.h"
#include "support/test_support.h"
#include "test_ddgi_scenes.h"

using namespace voxgi;

namespace {

int bits(float f) {
    int i;
    std::memcpy(&i, &f, sizeof i);
    return i;
}

// Every node's child boxes hold what lies below them, and every triangle is in one leaf.
void checkStructure(const Scene& scene, const TriangleBvh& bvh) {
    std::size_t triangles = 0;
    for (const Mesh& m : scene.meshes) triangles += m.triangleCount();
    std::set<std::uint32_t> seen(bvh.triangle.begin(), bvh.triangle.end());
    EXPECT_EQ(seen.size(), bvh.triangle.size());  // none twice
    // Degenerate triangles are left out (Sponza has one).
    EXPECT_LE(bvh.triangle.size(), triangles);
    EXPECT_GE(bvh.triangle.size() + triangles / 1000, triangles);
    ASSERT_EQ(bvh.corners.size(), 3 * bvh.triangle.size());
    int leaves = 0;
    for (std::size_t n = 0; n < bvh.nodeCount(); ++n)
        for (int c = 0; c < 2; ++c) {
            const glm::vec4 lo = bvh.nodes[4 * n + std::size_t(2 * c)], hi = bvh.nodes[4 * n + std::size_t(2 * c) + 1];
            const int first = bits(lo.w), count = bits(hi.w);
            if (first < 0) continue;
            auto inside = [&](glm::vec3 p) {
                return glm::all(glm::lessThanEqual(glm::vec3(lo), p)) && glm::all(glm::lessThanEqual(p, glm::vec3(hi)));
            };
            if (count > 0) {
                ++leaves;
                for (int k = first; k < first + count; ++k)
                    for (int v = 0; v < 3; ++v) EXPECT_TRUE(inside(glm::vec3(bvh.corners[std::size_t(3 * k + v)])));
            } else {
                ASSERT_LT(std::size_t(first), bvh.nodeCount());
                EXPECT_GT(std::size_t(first), n);  // depth first: children after parents
                for (int cc = 0; cc < 2; ++cc) {
                    const glm::vec4 clo = bvh.nodes[4 * std::size_t(first) + std::size_t(2 * cc)];
                    const glm::vec4 chi = bvh.nodes[4 * std::size_t(first) + std::size_t(2 * cc) + 1];
                    if (bits(clo.w) < 0) continue;
                    EXPECT_TRUE(inside(glm::vec3(clo)) && inside(glm::vec3(chi)));
                }
            }
        }
    EXPECT_GT(leaves, 0);
}

struct Agreement {
    int rays = 0, hitMismatch = 0, triangleMismatch = 0, sideMismatch = 0, hits = 0;
    int ties = 0;         // another triangle at the same distance (overlapping or coplanar faces)
    float worstT = 0.0f;  // relative distance difference where both hit the same triangle
};

// `count` rays from random points in the scene's bounds in random directions, some of them
// cut short, through the GPU traversal and through Embree.
Agreement compare(const Scene& scene, int count) {
    const TriangleBvh bvh = buildTriangleBvh(scene);
    checkStructure(scene, bvh);
    std::vector<std::size_t> meshFirst;
    std::size_t total = 0;
    for (const Mesh& m : scene.meshes) {
        meshFirst.push_back(total);
        total += m.triangleCount();
    }
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const Bounds b = scene.bounds();
    const float diagonal = glm::length(b.extent());
    std::vector<VolumeRay> rays;
    for (int i = 0; i < count; ++i) {
        const glm::vec3 o = b.min + glm::vec3(u(rng), u(rng), u(rng)) * b.extent();
        const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const glm::vec3 d(r * std::cos(phi), r * std::sin(phi), z);
        rays.push_back({o, i % 4 == 0 ? 0.1f * diagonal : 1e30f, d, 0.0f});  // some cut short
    }
    VolumeTracerGl gpu(scene, bvh);
    const std::vector<VolumeHit> hits = gpu.trace(rays, kMissDistance);

    RayTracer tracer(scene);
    Agreement a;
    for (int i = 0; i < count; ++i) {
        const VolumeRay& ray = rays[std::size_t(i)];
        const RayHit e = tracer.intersect(ray.origin, ray.direction, 0.0f, ray.tMax);
        const VolumeHit& g = hits[std::size_t(i)];
        const int slot = bits(g.triangle);
        ++a.rays;
        if (e.hit != (slot >= 0)) {
            ++a.hitMismatch;
            continue;
        }
        if (!e.hit) continue;
        ++a.hits;
        const float dt = std::abs(std::abs(g.distance) - e.t) / e.t;
        // Sponza's ties are faces back to back (the other side of the same wall).
        if (bvh.triangle[std::size_t(slot)] != meshFirst[e.mesh] + e.triangle) {
            ++(dt < 1e-5f ? a.ties : a.triangleMismatch);
            continue;
        }
        if (e.frontFace != (g.distance >= 0.0f)) ++a.sideMismatch;
        a.worstT = std::max(a.worstT, dt);
    }
    std::printf("%d rays, %d hits: %d hit/miss, %d triangle (and %d ties) and %d side mismatches; worst distance "
                "%.2e relative\n",
                a.rays, a.hits, a.hitMismatch, a.triangleMismatch, a.ties, a.sideMismatch, double(a.worstT));
    return a;
}

}  // namespace

class DdgiTriangleBvh : public ::testing::Test {
protected:
    static void SetUpTestSuite() { test::useHeadlessContext(); }
};

TEST_F(DdgiTriangleBvh, CornellBoxRaysFindEmbreesTriangles) {
    const Scene scene = loadSceneFile(std::string(VOXGI_SOURCE_DIR) + "/scenes/cornell-box.json");
    const Agreement a = compare(scene, 8192);
    ASSERT_GT(a.hits, 4000);
    // Rays through a shared edge may take either triangle: a handful at most.
    EXPECT_LE(a.hitMismatch, a.rays / 1000);
    EXPECT_LE(a.triangleMismatch, a.hits / 1000);  // 0 measured
    EXPECT_EQ(a.sideMismatch, 0);
    EXPECT_LT(a.worstT, 1e-4f);
}

TEST_F(DdgiTriangleBvh, SponzaRaysFindEmbreesTriangles) {
    if (test::sharedScenesDir().empty()) GTEST_SKIP() << "../shared/scenes not present";
    const Scene scene = loadSceneFile(std::string(VOXGI_SOURCE_DIR) + "/scenes/sponza.json");
    const Agreement a = compare(scene, 8192);
    ASSERT_GT(a.hits, 4000);
    EXPECT_LE(a.hitMismatch, a.rays / 1000);
    EXPECT_LE(a.triangleMismatch, a.hits / 1000);  // 0 measured, 63 ties at the same distance
    EXPECT_EQ(a.sideMismatch, 0);
    EXPECT_LT(a.worstT, 1e-3f);
}

// A scene of one triangle: the root holds a single leaf.
TEST_F(DdgiTriangleBvh, OneTriangleIsOneLeaf) {
    Scene scene = test::twoRooms();
    scene.meshes.resize(1);
    Mesh& m = scene.meshes[0];
    m.indices.resize(3);
    m.materialIds.resize(1);
    const Agreement a = compare(scene, 1024);
    EXPECT_EQ(a.hitMismatch, 0);
    EXPECT_EQ(a.triangleMismatch, 0);
}
