#include "gi/raytrace/ray_tracer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "gi/raytrace/texture_pyramid.h"
#include "scenes/large_pages.h"
#include "scenes/memory_limit.h"

namespace voxgi {

namespace {
// A triangle's vertices and unit geometric normal in one cache line: the hit record's chain of
// misses (the index, then each vertex) was the most of its time on big scenes.
struct alignas(64) TriangleCorners {
    glm::vec3 a{0.0f}, b{0.0f}, c{0.0f};
    glm::vec3 geometricNormal{0.0f};  // normalize(cross(b - a, c - a))
};
}  // namespace

struct RayTracer::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    // Built on the first cone lookup: most users (the path tracer) never need them.
    std::once_flag conesOnce;
    std::atomic<bool> conesBuilt{false};
    std::vector<std::unique_ptr<TexturePyramid>> pyramids;  // per texture
    // Per triangle of a textured material, texels of its texture per unit length (0: no uvs
    // or untextured); a mesh's triangles start at meshFirst[mesh].
    std::vector<float> texelScale;
    std::vector<std::size_t> meshFirst;  // set by the constructor
    std::size_t allTriangles = 0;        // over all meshes, degenerate ones included
    // Per triangle, from meshFirst: what a hit record reads, one cache line each and no index
    // to follow (built with the scene: every intersect() needs them).
    // Read at random by every hit: in large pages (scenes/large_pages.h).
    LargeVector<TriangleSurface> surfaces;
    LargeVector<TriangleCorners> corners;
    std::atomic<bool> logging{false};
    tbb::enumerable_thread_specific<std::vector<LoggedRay>> log;
    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {
void errorHandler(void*, RTCError code, const char* message) {
    if (code != RTC_ERROR_NONE) std::fprintf(stderr, "voxgi: embree error %d: %s\n", int(code), message ? message : "");
}

RTCRay makeRay(glm::vec3 o, glm::vec3 d, float tMin, float tMax) {
    RTCRay ray;
    ray.org_x = o.x;
    ray.org_y = o.y;
    ray.org_z = o.z;
    ray.dir_x = d.x;
    ray.dir_y = d.y;
    ray.dir_z = d.z;
    ray.tnear = tMin;
    ray.tfar = tMax;
    ray.time = 0.0f;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
    return ray;
}

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
}  // namespace

RayTracer::RayTracer(const Scene& scene) : impl_(std::make_unique<Impl>()), scene_(scene) {
    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device) throw std::runtime_error("cannot create an Embree device");
    rtcSetDeviceErrorFunction(impl_->device, errorHandler, nullptr);
    impl_->scene = rtcNewScene(impl_->device);
    impl_->meshFirst.resize(scene.meshes.size());
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        impl_->meshFirst[m] = impl_->allTriangles;
        impl_->allTriangles += scene.meshes[m].triangleCount();
    }
    requireMemory(double(impl_->allTriangles) * double(sizeof(TriangleSurface) + sizeof(TriangleCorners)),
                  "ray tracer: hit records of " + std::to_string(impl_->allTriangles) + " triangles");
    impl_->surfaces.resize(impl_->allTriangles);
    impl_->corners.resize(impl_->allTriangles);
    tbb::parallel_for(std::size_t(0), scene.meshes.size(), [&](std::size_t m) {
        const Mesh& mesh = scene.meshes[m];
        TriangleSurface* surface = &impl_->surfaces[impl_->meshFirst[m]];
        TriangleCorners* corners = &impl_->corners[impl_->meshFirst[m]];
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const std::uint32_t* tri = &mesh.indices[3 * t];
            for (int k = 0; k < 3; ++k) {
                if (!mesh.normals.empty()) surface[t].normals[k] = mesh.normals[tri[k]];
                if (!mesh.uvs.empty()) surface[t].uvs[k] = mesh.uvs[tri[k]];
            }
            surface[t].material = mesh.materialIds[t];
            TriangleCorners& k = corners[t];
            k.a = mesh.positions[tri[0]];
            k.b = mesh.positions[tri[1]];
            k.c = mesh.positions[tri[2]];
            k.geometricNormal = glm::normalize(glm::cross(k.b - k.a, k.c - k.a));
        }
    });
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), mesh.positions.size()));
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            // Embree skips triangles with non-finite vertices; make that explicit and counted.
            glm::vec3 p = mesh.positions[i];
            v[3 * i] = p.x;
            v[3 * i + 1] = p.y;
            v[3 * i + 2] = p.z;
        }
        auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), mesh.triangleCount()));
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            const glm::vec3& a = mesh.positions[mesh.indices[3 * t]];
            const glm::vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
            const glm::vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
            bool valid = finite(a) && finite(b) && finite(c) && glm::length(glm::cross(b - a, c - a)) > 0.0f;
            for (int k = 0; k < 3; ++k) idx[3 * t + std::size_t(k)] = mesh.indices[3 * t + std::size_t(k)];
            if (!valid) {
                // A degenerate triangle (all indices equal) is ignored by the BVH builder.
                idx[3 * t + 1] = idx[3 * t + 2] = idx[3 * t];
            } else {
                ++triangles_;
            }
        }
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(impl_->scene, geom, unsigned(m));
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(impl_->scene);
}

RayTracer::~RayTracer() = default;

float surfaceRayOffset(const Scene& scene) {
    const Bounds b = scene.bounds();
    const float radius = b.valid() ? 0.5f * glm::length(b.extent()) : 0.0f;
    return 1e-4f * (radius > 0.0f ? radius : 1.0f);
}

namespace {
// Embree's nearest hit along one ray.
RTCRayHit nearest(RTCScene scene, RTCIntersectContext& context, glm::vec3 o, glm::vec3 d, float tMin, float tMax) {
    RTCRayHit rh;
    rh.ray = makeRay(o, d, tMin, tMax);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    return rh;
}

RawHit toRawHit(const RTCRayHit& rh) {
    RawHit raw;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return raw;
    raw.t = rh.ray.tfar;
    raw.mesh = rh.hit.geomID;
    raw.triangle = rh.hit.primID;
    raw.u = rh.hit.u;
    raw.v = rh.hit.v;
    // Embree's Ng points the way cross(v1 - v0, v2 - v0) does (tests/test_ray_tracer.cpp checks).
    raw.normal = glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    return raw;
}

// The hit record: loads from two lines per triangle and square roots, so callers with many
// rays build them after tracing a batch. Written in place: a record built aside and copied
// whole would be read back before its fields left the store buffer.
void makeHit(const Scene& scene, const TriangleSurface* surfaces, const TriangleCorners* corners,
             const std::vector<std::size_t>& meshFirst, const RawHit& raw, glm::vec3 d, RayHit& hit) {
    hit = RayHit{};
    if (!raw.hit()) return;
    hit.hit = true;
    hit.t = raw.t;
    hit.mesh = raw.mesh;
    hit.triangle = raw.triangle;
    const Mesh& mesh = scene.meshes[hit.mesh];
    const std::size_t index = meshFirst[hit.mesh] + hit.triangle;
    const TriangleCorners& k = corners[index];
    const TriangleSurface& surface = surfaces[index];
    const glm::vec3 &a = k.a, &b = k.b, &c = k.c;
    const float u = raw.u, v = raw.v, w = 1.0f - u - v;
    hit.position = w * a + u * b + v * c;
    hit.geometricNormal = k.geometricNormal;
    hit.frontFace = glm::dot(hit.geometricNormal, d) < 0.0f;
    hit.shadingNormal = hit.geometricNormal;
    hit.smoothPosition = hit.position;
    if (!mesh.normals.empty()) {
        const glm::vec3 &na = surface.normals[0], &nb = surface.normals[1], &nc = surface.normals[2];
        glm::vec3 n = w * na + u * nb + v * nc;
        float len = glm::length(n);
        if (len > 0.0f && std::isfinite(len)) {
            hit.shadingNormal = n / len;
            const glm::vec3 p = hit.position;
            auto onTangentPlane = [&](const glm::vec3& vertex, const glm::vec3& normal) {
                return p - std::min(glm::dot(p - vertex, normal), 0.0f) * normal;
            };
            const glm::vec3 smooth = w * onTangentPlane(a, na) + u * onTangentPlane(b, nb) + v * onTangentPlane(c, nc);
            if (glm::dot(smooth - p, hit.geometricNormal) * glm::dot(hit.shadingNormal, hit.geometricNormal) > 0.0f &&
                std::isfinite(smooth.x + smooth.y + smooth.z))
                hit.smoothPosition = smooth;
        }
    }
    if (!mesh.uvs.empty()) hit.uv = w * surface.uvs[0] + u * surface.uvs[1] + v * surface.uvs[2];
    hit.material = surface.material;
}
}  // namespace

RayHit RayTracer::intersect(glm::vec3 o, glm::vec3 d, float tMin, float tMax) const {
    if (impl_->logging.load(std::memory_order_relaxed)) impl_->log.local().push_back({o, tMin, d, tMax, false});
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RayHit hit;
    makeHit(scene_, impl_->surfaces.data(), impl_->corners.data(), impl_->meshFirst,
            toRawHit(nearest(impl_->scene, context, o, d, tMin, tMax)), d, hit);
    return hit;
}

void RayTracer::traceFan(glm::vec3 o, const glm::vec3* d, int n, RawHit* hits, const TriangleSurface** surfaces) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (int i = 0; i < n; ++i) {
        hits[i] = toRawHit(nearest(impl_->scene, context, o, d[i], 0.0f, 1e30f));
        if (!surfaces) continue;
        // The line's miss overlaps with the next traversals instead of stalling its reader.
        const TriangleSurface* surface =
            hits[i].hit() ? &impl_->surfaces[impl_->meshFirst[hits[i].mesh] + hits[i].triangle] : nullptr;
        if (surface) __builtin_prefetch(surface);
        surfaces[i] = surface;
    }
}

void RayTracer::intersectFan(glm::vec3 o, const glm::vec3* d, int n, RayHit* hits) const {
    // Built one ray at a time, a record's load-and-sqrt chain right after its traversal leaves
    // the next traversal waiting (about a fifth of a probe ray's time); built after the batch,
    // the records of different rays overlap.
    constexpr int kBatch = 64;
    RawHit raw[kBatch];
    for (int first = 0; first < n; first += kBatch) {
        const int count = std::min(kBatch, n - first);
        traceFan(o, d + first, count, raw);
        for (int i = 0; i < count; ++i)
            makeHit(scene_, impl_->surfaces.data(), impl_->corners.data(), impl_->meshFirst, raw[i], d[first + i],
                    hits[first + i]);
    }
}

RawHit RayTracer::intersectRaw(glm::vec3 o, glm::vec3 d) const {
    if (impl_->logging.load(std::memory_order_relaxed)) impl_->log.local().push_back({o, 0.0f, d, 1e30f, false});
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    return toRawHit(nearest(impl_->scene, context, o, d, 0.0f, 1e30f));
}

void RayTracer::prefetchRecord(const RawHit& raw) const {
    if (!raw.hit()) return;
    const std::size_t index = impl_->meshFirst[raw.mesh] + raw.triangle;
    __builtin_prefetch(&impl_->corners[index]);
    __builtin_prefetch(&impl_->surfaces[index]);
}

void RayTracer::hitRecord(const RawHit& raw, glm::vec3 d, RayHit& hit) const {
    makeHit(scene_, impl_->surfaces.data(), impl_->corners.data(), impl_->meshFirst, raw, d, hit);
}

void RayTracer::intersectCoherent(const glm::vec3* origins, const glm::vec3* directions, int n, RayHit* hits) const {
    const bool logging = impl_->logging.load(std::memory_order_relaxed);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    constexpr int kBatch = 64;
    RTCRayHit batch[kBatch];
    for (int first = 0; first < n; first += kBatch) {
        const int count = std::min(kBatch, n - first);
        for (int i = 0; i < count; ++i) {
            const glm::vec3 o = origins[first + i], d = directions[first + i];
            if (logging) impl_->log.local().push_back({o, 0.0f, d, 1e30f, false});
            batch[i].ray = makeRay(o, d, 0.0f, 1e30f);
            batch[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
            batch[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect1M(impl_->scene, &context, batch, unsigned(count), sizeof(RTCRayHit));
        for (int i = 0; i < count; ++i)
            makeHit(scene_, impl_->surfaces.data(), impl_->corners.data(), impl_->meshFirst, toRawHit(batch[i]),
                    directions[first + i], hits[first + i]);
    }
}

float RayTracer::nearestHit(glm::vec3 o, glm::vec3 d) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    const RTCRayHit rh = nearest(impl_->scene, context, o, d, 0.0f, 1e30f);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? INFINITY : rh.ray.tfar;
}

bool RayTracer::occluded(glm::vec3 o, glm::vec3 d, float tMin, float tMax) const {
    if (impl_->logging.load(std::memory_order_relaxed)) impl_->log.local().push_back({o, tMin, d, tMax, true});
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = makeRay(o, d, tMin, tMax);
    rtcOccluded1(impl_->scene, &context, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();
}

void RayTracer::startLog() const {
    impl_->log.clear();
    impl_->logging.store(true);
}

std::vector<LoggedRay> RayTracer::stopLog() const {
    impl_->logging.store(false);
    std::vector<LoggedRay> all;
    for (std::vector<LoggedRay>& part : impl_->log) all.insert(all.end(), part.begin(), part.end());
    impl_->log.clear();
    return all;
}

std::size_t RayTracer::replayBare(const std::vector<LoggedRay>& rays) const {
    tbb::combinable<std::size_t> hits([] { return std::size_t(0); });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        std::size_t local = 0;
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            const LoggedRay& ray = rays[i];
            if (ray.occlusion) {
                RTCRay q = makeRay(ray.origin, ray.direction, ray.tMin, ray.tMax);
                rtcOccluded1(impl_->scene, &context, &q);
                local += q.tfar < 0.0f ? 1 : 0;
            } else {
                local += nearest(impl_->scene, context, ray.origin, ray.direction, ray.tMin, ray.tMax).hit.geomID !=
                                 RTC_INVALID_GEOMETRY_ID
                             ? 1
                             : 0;
            }
        }
        hits.local() += local;
    });
    return hits.combine([](std::size_t a, std::size_t b) { return a + b; });
}

void RayTracer::prepareCones() const {
    std::call_once(impl_->conesOnce, [&] {
        impl_->pyramids.resize(scene_.textures.size());
        tbb::parallel_for(std::size_t(0), scene_.textures.size(), [&](std::size_t i) {
            impl_->pyramids[i] = std::make_unique<TexturePyramid>(scene_.textures[i]);
        });
        impl_->texelScale.assign(impl_->allTriangles, 0.0f);
        tbb::parallel_for(std::size_t(0), scene_.meshes.size(), [&](std::size_t m) {
            const Mesh& mesh = scene_.meshes[m];
            if (mesh.uvs.empty()) return;
            float* scale = &impl_->texelScale[impl_->meshFirst[m]];
            for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
                const int texture = scene_.materials[mesh.materialIds[t]].albedoTexture;
                if (texture < 0) continue;
                const std::uint32_t* tri = &mesh.indices[3 * t];
                scale[t] = triangleTexelScale(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]],
                                              mesh.uvs[tri[0]], mesh.uvs[tri[1]], mesh.uvs[tri[2]], 1, 1) *
                           impl_->pyramids[std::size_t(texture)]->texelScale();
            }
        });
        impl_->conesBuilt.store(true, std::memory_order_release);
    });
}

const TriangleSurface& RayTracer::surface(const RawHit& hit) const {
    return impl_->surfaces[impl_->meshFirst[hit.mesh] + hit.triangle];
}

glm::vec3 RayTracer::coneAlbedo(std::uint32_t material, std::size_t triangle, glm::vec2 uv, float t, float cosine,
                                float spread) const {
    const Material& m = scene_.materials[material];
    if (m.albedoTexture < 0) return m.albedo;
    if (!impl_->conesBuilt.load(std::memory_order_acquire)) prepareCones();
    const TexturePyramid& pyramid = *impl_->pyramids[std::size_t(m.albedoTexture)];
    const float scale = impl_->texelScale[triangle];
    if (!(scale > 0.0f)) return m.albedo * scene_.textures[std::size_t(m.albedoTexture)].sampleLinear(uv);
    const float footprint = rayConeFootprint(scale, t * spread, cosine);
    return m.albedo * pyramid.sample(uv, pyramid.levelForFootprint(footprint));
}

glm::vec3 RayTracer::albedoInCone(const RayHit& hit, glm::vec3 direction, float spread) const {
    return coneAlbedo(hit.material, impl_->meshFirst[hit.mesh] + hit.triangle, hit.uv, hit.t,
                      glm::dot(hit.geometricNormal, direction), spread);
}

glm::vec3 RayTracer::albedoInCone(const RawHit& hit, const TriangleSurface& surface, glm::vec3 direction,
                                  float spread) const {
    return coneAlbedo(surface.material, impl_->meshFirst[hit.mesh] + hit.triangle, surface.uv(hit.u, hit.v), hit.t,
                      glm::dot(hit.normal, direction) / glm::length(hit.normal), spread);
}

void RayTracer::prefetchAlbedo(const RayHit& hit) const {
    const Material& m = scene_.materials[hit.material];
    if (m.albedoTexture >= 0) scene_.textures[std::size_t(m.albedoTexture)].prefetch(hit.uv);
}

glm::vec3 RayTracer::albedoAt(const RayHit& hit) const {
    const Material& m = scene_.materials[hit.material];
    if (m.albedoTexture < 0) return m.albedo;
    return m.albedo * scene_.textures[std::size_t(m.albedoTexture)].sampleLinear(hit.uv);
}

}  // namespace voxgi
