// RayTracer's batched queries (traceFan, intersectFan) against the one-ray intersect(): the same
// hits, Embree's geometric normal on the same side as the record's, and the triangles' surface
// copies agreeing with the record.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gi/raytrace/ray_tracer.h"
#include "gi/sampling/sequences.h"
#include "scenes/scene.h"

using namespace voxgi;

namespace {

// Randomly placed and oriented triangles around the origin, half of the meshes with vertex
// normals and texture coordinates, so every branch of the hit record runs.
Scene triangleSoup(std::uint32_t seed) {
    Scene scene;
    scene.materials.push_back(Material{});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int m = 0; m < 4; ++m) {
        Mesh mesh;
        mesh.name = "soup" + std::to_string(m);
        for (int t = 0; t < 60; ++t) {
            glm::vec3 centre = 3.0f * glm::vec3(u(rng), u(rng), u(rng));
            for (int k = 0; k < 3; ++k) {
                mesh.positions.push_back(centre + 0.6f * glm::vec3(u(rng), u(rng), u(rng)));
                if (m % 2) {
                    const glm::vec3 n(u(rng), u(rng), u(rng));
                    mesh.normals.push_back(glm::normalize(n + glm::vec3(0.0f, 0.0f, 0.01f)));
                    mesh.uvs.push_back(glm::vec2(u(rng), u(rng)));
                }
                mesh.indices.push_back(std::uint32_t(mesh.indices.size()));
            }
            mesh.materialIds.push_back(0);
        }
        scene.meshes.push_back(mesh);
    }
    return scene;
}

// Every field of two hit records equal, bit for bit.
void expectSameRecord(const RayHit& a, const RayHit& b, int ray) {
    EXPECT_EQ(a.t, b.t) << "ray " << ray;
    EXPECT_EQ(a.position, b.position) << "ray " << ray;
    EXPECT_EQ(a.geometricNormal, b.geometricNormal) << "ray " << ray;
    EXPECT_EQ(a.shadingNormal, b.shadingNormal) << "ray " << ray;
    EXPECT_EQ(a.smoothPosition, b.smoothPosition) << "ray " << ray;
    EXPECT_EQ(a.uv, b.uv) << "ray " << ray;
    EXPECT_EQ(a.frontFace, b.frontFace) << "ray " << ray;
    EXPECT_EQ(a.material, b.material) << "ray " << ray;
}

}  // namespace

TEST(RayTracer, FansFindTheHitsOfSingleRays) {
    const Scene scene = triangleSoup(7);
    const RayTracer tracer(scene);
    const int n = 200;  // more than one internal batch of intersectFan
    std::vector<glm::vec3> directions;
    for (int i = 0; i < n; ++i) directions.push_back(sphericalFibonacci(i, n));
    for (glm::vec3 origin : {glm::vec3(0.0f), glm::vec3(0.3f, -0.2f, 0.5f), glm::vec3(5.0f, 0.0f, 0.0f)}) {
        std::vector<RawHit> raw(static_cast<std::size_t>(n));
        std::vector<RayHit> records(static_cast<std::size_t>(n));
        std::vector<const TriangleSurface*> surfaces(static_cast<std::size_t>(n));
        tracer.traceFan(origin, directions.data(), n, raw.data(), surfaces.data());
        tracer.intersectFan(origin, directions.data(), n, records.data());
        int hits = 0, backfaces = 0;
        for (int i = 0; i < n; ++i) {
            const RayHit one = tracer.intersect(origin, directions[std::size_t(i)]);
            const RawHit& r = raw[std::size_t(i)];
            const RayHit& fan = records[std::size_t(i)];
            ASSERT_EQ(r.hit(), one.hit) << "ray " << i;
            ASSERT_EQ(surfaces[std::size_t(i)] != nullptr, one.hit) << "ray " << i;
            ASSERT_EQ(fan.hit, one.hit) << "ray " << i;
            if (!one.hit) continue;
            ++hits;
            backfaces += !one.frontFace;
            EXPECT_EQ(r.t, one.t);
            EXPECT_EQ(r.mesh, one.mesh);
            EXPECT_EQ(r.triangle, one.triangle);
            // Embree's normal is on the record's side: front faces agree whichever one decides.
            EXPECT_GT(glm::dot(glm::normalize(r.normal), one.geometricNormal), 0.9999f) << "ray " << i;
            EXPECT_EQ(glm::dot(r.normal, directions[std::size_t(i)]) < 0.0f, one.frontFace) << "ray " << i;
            // The triangle's surface copy gives the record's material, uv and shading normal.
            const TriangleSurface* surface = surfaces[std::size_t(i)];
            ASSERT_EQ(surface, &tracer.surface(r));
            EXPECT_EQ(surface->material, one.material);
            const glm::vec2 uv = surface->uv(r.u, r.v);
            EXPECT_NEAR(uv.x, one.uv.x, 1e-5f);
            EXPECT_NEAR(uv.y, one.uv.y, 1e-5f);
            if (scene.meshes[one.mesh].normals.empty()) {
                EXPECT_EQ(surface->normal(r.u, r.v), glm::vec3(0.0f));
            } else {
                const glm::vec3 n = glm::normalize(surface->normal(r.u, r.v));
                EXPECT_GT(glm::dot(n, one.shadingNormal), 0.99999f) << "ray " << i;
            }
            // The batched records are the one-ray records, bit for bit.
            expectSameRecord(fan, one, i);
        }
        // The soup is dense enough that both sides of triangles are hit from inside it.
        if (origin.x < 4.0f) {
            EXPECT_GT(hits, n / 4);
            EXPECT_GT(backfaces, 0);
            EXPECT_LT(backfaces, hits);
        }
    }
}

TEST(RayTracer, RecordsBuiltLaterAndCoherentStreamsFindTheHitsOfSingleRays) {
    const Scene scene = triangleSoup(11);
    const RayTracer tracer(scene);
    const int n = 150;  // more than one internal batch of intersectCoherent
    std::vector<glm::vec3> origins, directions;
    for (int i = 0; i < n; ++i) {
        // Neighbouring rays from nearby origins, as a tile's camera rays, and some far apart.
        origins.push_back(glm::vec3(0.01f * float(i % 10), 0.01f * float(i / 10), 6.0f) + (i % 13 == 0 ? glm::vec3(-9.0f, 0.0f, -6.0f) : glm::vec3(0.0f)));
        directions.push_back(glm::normalize(glm::vec3(0.03f * float(i % 10) - 0.15f, 0.03f * float(i / 10) - 0.2f, -1.0f)));
    }
    std::vector<RayHit> coherent(static_cast<std::size_t>(n));
    tracer.intersectCoherent(origins.data(), directions.data(), n, coherent.data());
    int hits = 0;
    for (int i = 0; i < n; ++i) {
        const RayHit one = tracer.intersect(origins[std::size_t(i)], directions[std::size_t(i)]);
        RayHit later;
        tracer.hitRecord(tracer.intersectRaw(origins[std::size_t(i)], directions[std::size_t(i)]), directions[std::size_t(i)],
                         later);
        // Built later, the record is the same bit for bit.
        ASSERT_EQ(later.hit, one.hit) << "ray " << i;
        expectSameRecord(later, one, i);
        // Traced in packets: the same triangle; Embree's SIMD tests may round differently.
        const RayHit& c = coherent[std::size_t(i)];
        ASSERT_EQ(c.hit, one.hit) << "ray " << i;
        if (!one.hit) continue;
        ++hits;
        EXPECT_EQ(c.mesh, one.mesh) << "ray " << i;
        EXPECT_EQ(c.triangle, one.triangle) << "ray " << i;
        EXPECT_EQ(c.frontFace, one.frontFace) << "ray " << i;
        EXPECT_NEAR(c.t, one.t, 1e-5f * one.t) << "ray " << i;
        EXPECT_LT(glm::length(c.position - one.position), 1e-5f) << "ray " << i;
    }
    EXPECT_GT(hits, n / 4);
    EXPECT_LT(hits, n);
}

TEST(RayTracer, EmptyFansWriteNothing) {
    const Scene scene = triangleSoup(3);
    const RayTracer tracer(scene);
    RawHit raw;
    raw.t = 42.0f;
    tracer.traceFan(glm::vec3(0.0f), nullptr, 0, &raw);
    EXPECT_EQ(raw.t, 42.0f);
}
