// Embree 3 over a voxgi Scene: the one place CPU rays are traced (path tracer, DDGI probe rays,
// sky occlusion, hybrid reflections). Thread-safe for concurrent queries after construction.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi {

struct RayHit {
    bool hit = false;
    float t = 0.0f;
    glm::vec3 position{0.0f};
    glm::vec3 geometricNormal{0.0f};  // unit, from the triangle's winding (front = counter-clockwise)
    glm::vec3 shadingNormal{0.0f};    // unit, interpolated vertex normal (or the geometric one)
    // Where rays leaving towards the side the vertex normals face start from: the point of the
    // smooth surface those normals describe (Hanika 2021's shadow-terminator fix: the barycentric
    // blend of the hit projected onto each vertex's tangent plane) where that surface bulges
    // out of the triangle, else `position`. A low-poly sphere lit at a grazing angle then casts
    // no facet-shaped shadows onto itself.
    glm::vec3 smoothPosition{0.0f};
    glm::vec2 uv{0.0f};
    bool frontFace = true;            // the ray arrived against the geometric normal
    std::uint32_t mesh = 0;           // index into Scene::meshes
    std::uint32_t triangle = 0;       // triangle within that mesh
    std::uint32_t material = 0;       // index into Scene::materials
};

// What Embree returns for one ray, before a hit record is built: for callers that need only
// part of the record (probe rays: distance, facing, normal, material).
struct RawHit {
    static constexpr std::uint32_t kNoMesh = 0xFFFFFFFFu;
    float t = 0.0f;
    std::uint32_t mesh = kNoMesh;  // kNoMesh: a miss
    std::uint32_t triangle = 0;
    float u = 0.0f, v = 0.0f;      // barycentric weights of the triangle's second and third vertex
    glm::vec3 normal{0.0f};        // geometric, not normalised; the front side is counter-clockwise
    bool hit() const { return mesh != kNoMesh; }
};

// A copy of one triangle's surface attributes in one cache line, for batches of rays that hit
// random triangles of big meshes (probe rays): one cache miss per hit, prefetched while later
// rays are traced, instead of a chain of misses (indices, then each vertex attribute).
struct alignas(64) TriangleSurface {
    glm::vec3 normals[3]{glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(0.0f)};  // zero without vertex normals
    glm::vec2 uvs[3]{glm::vec2(0.0f), glm::vec2(0.0f), glm::vec2(0.0f)};        // zero without uvs
    std::uint32_t material = 0;

    // The interpolated vertex normal at barycentric (u, v), not normalised (zero without them).
    glm::vec3 normal(float u, float v) const { return (1.0f - u - v) * normals[0] + u * normals[1] + v * normals[2]; }
    glm::vec2 uv(float u, float v) const { return (1.0f - u - v) * uvs[0] + u * uvs[1] + v * uvs[2]; }
};

// One query a RayTracer answered (intersect or occluded), for replaying the same rays through
// Embree alone: how much of a renderer's time Embree itself takes (voxgi bench pathtrace).
struct LoggedRay {
    glm::vec3 origin{0.0f};
    float tMin = 0.0f;
    glm::vec3 direction{0.0f};
    float tMax = 0.0f;
    bool occlusion = false;
};

class RayTracer {
public:
    explicit RayTracer(const Scene& scene);
    ~RayTracer();
    RayTracer(const RayTracer&) = delete;
    RayTracer& operator=(const RayTracer&) = delete;

    RayHit intersect(glm::vec3 origin, glm::vec3 direction, float tMin = 0.0f, float tMax = 1e30f) const;
    // intersect() in steps: Embree's nearest hit (tMin 0, tMax 1e30); a request for the cache
    // lines its hit record reads; the record (`direction` the ray's). Callers with many rays
    // request the lines of all their hits in one go, so the misses overlap.
    RawHit intersectRaw(glm::vec3 origin, glm::vec3 direction) const;
    void prefetchRecord(const RawHit& raw) const;
    void hitRecord(const RawHit& raw, glm::vec3 direction, RayHit& hit) const;
    // Embree's nearest hits of n rays from one origin (tMin 0, tMax 1e30). With `surfaces`, also
    // each hit's TriangleSurface (null for a miss), prefetched while the next rays are traced.
    void traceFan(glm::vec3 origin, const glm::vec3* directions, int n, RawHit* hits,
                  const TriangleSurface** surfaces = nullptr) const;
    // intersect() of n rays from one origin (tMin 0, tMax 1e30), hits[i] for directions[i]:
    // the same records, in less time than n calls (they are built after a batch is traced).
    void intersectFan(glm::vec3 origin, const glm::vec3* directions, int n, RayHit* hits) const;
    // intersect() of n rays (tMin 0, tMax 1e30), hits[i] for origins[i], directions[i], traced
    // as one coherent stream: Embree packs neighbouring rays into SIMD packets that share their
    // traversal. For rays that start close together and point alike (a tile's camera rays);
    // slower than n intersect() calls for scattered rays.
    void intersectCoherent(const glm::vec3* origins, const glm::vec3* directions, int n, RayHit* hits) const;
    bool occluded(glm::vec3 origin, glm::vec3 direction, float tMin, float tMax) const;
    // The distance to the nearest hit (infinity for a miss) and nothing else: Embree's own cost
    // of a ray, without the hit record intersect() builds (benchmarks compare against it).
    float nearestHit(glm::vec3 origin, glm::vec3 direction) const;

    // While logging, every intersect() and occluded() call is recorded (per thread, in order).
    void startLog() const;
    std::vector<LoggedRay> stopLog() const;
    // Embree's rtcIntersect1 / rtcOccluded1 on each ray and nothing else, over all threads;
    // returns the number of hits (so the work cannot be optimised away).
    std::size_t replayBare(const std::vector<LoggedRay>& rays) const;

    // Material albedo at a hit, times the diffuse texture when there is one.
    glm::vec3 albedoAt(const RayHit& hit) const;
    // Starts loading the texels albedoAt(hit) reads: a texture lookup's cache miss was most of
    // its cost, and callers have other work to do before they need the value.
    void prefetchAlbedo(const RayHit& hit) const;
    // The same averaged over the footprint of a ray cone of apex angle `spread` (radians) that
    // travelled hit.t along unit `direction` (texture mip pyramids, gi/raytrace/texture_pyramid.h).
    glm::vec3 albedoInCone(const RayHit& hit, glm::vec3 direction, float spread) const;
    // The surface of a raw hit's triangle (64 bytes per triangle of the scene, built with it).
    const TriangleSurface& surface(const RawHit& hit) const;
    // albedoInCone at a raw hit on `surface`, its triangle.
    glm::vec3 albedoInCone(const RawHit& hit, const TriangleSurface& surface, glm::vec3 direction, float spread) const;
    const Scene& scene() const { return scene_; }
    // Triangles Embree accepted (NaN or degenerate ones are left out).
    std::size_t triangleCount() const { return triangles_; }

private:
    void prepareCones() const;
    glm::vec3 coneAlbedo(std::uint32_t material, std::size_t triangle, glm::vec2 uv, float t, float cosine,
                         float spread) const;
    struct Impl;
    std::unique_ptr<Impl> impl_;
    const Scene& scene_;
    std::size_t triangles_ = 0;
};

// How far rays leaving a surface start off it along its normal (and stop short of what they
// aim at): relative to the scene's size, with no absolute floor that a tiny scene would feel
// (1e-4 of the bounds' half diagonal; 1e-4 for a scene of one point).
float surfaceRayOffset(const Scene& scene);

}  // namespace voxgi
