#include "gi/ddgi/probe_rays.h"

#include <cmath>
#include <optional>
#include <random>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/ddgi/hit_cache.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/raytrace/texture_pyramid.h"
#include "gi/sampling/sequences.h"
#include "scenes/errors.h"
#include "shaders/shared/material.h"

namespace voxgi {

namespace {

struct Emitters {
    std::vector<std::uint16_t> material;  // ProbeTrace::emission entry per material (0: none)
    std::vector<char> mesh;               // the mesh's emission counts (not an analytic light's quad)
};

// One ray's hit into its surfel (and its hit position, for the hit cache). `spread` is the ray's
// cone angle for the albedo lookup; negative for classification rays, which are never shaded
// (albedo 0, no lookup).
void toSurfel(const RayTracer& tracer, const Emitters& emitters, const RawHit& raw, const TriangleSurface* triangle,
              glm::vec3 origin, glm::vec3 d, float spread, ProbeSurfel& s, glm::vec3* position) {
    if (!raw.hit()) {
        s = ProbeSurfel{};
        return;
    }
    s.emitter = 0;
    s.albedo[0] = s.albedo[1] = s.albedo[2] = 0;
    if (!(glm::dot(raw.normal, d) < 0.0f)) {
        s.distance = -raw.t;
        s.normal = glm::vec3(0.0f);
        return;
    }
    // Only what a surfel needs of the hit record, from the triangle's one-line copy of its
    // attributes: no vertex positions (Embree gives the geometric normal, the position is on
    // the ray), texture coordinates only for textures.
    const TriangleSurface& surface = *triangle;
    s.distance = raw.t;
    *position = origin + raw.t * d;
    glm::vec3 n = surface.normal(raw.u, raw.v);
    float length = glm::length(n);
    if (!(length > 0.0f && std::isfinite(length))) {  // no vertex normals (or degenerate ones)
        n = raw.normal;
        length = glm::length(n);
    }
    n /= length;
    s.normal = glm::dot(n, d) > 0.0f ? -n : n;
    if (spread < 0.0f) return;
    const Material& m = tracer.scene().materials[surface.material];
    const glm::vec3 albedo = m.albedoTexture >= 0 ? tracer.albedoInCone(raw, surface, d, spread) : m.albedo;
    s.setDiffuseAlbedo(shading::diffuseAlbedo(albedo, m.metallic, m.specular, m.transmission));
    s.emitter = emitters.mesh[raw.mesh] ? emitters.material[surface.material] : 0;
}

}  // namespace

glm::mat3 randomRotation(std::uint32_t seed, std::uint32_t frame) {
    // Shoemake's uniform random unit quaternion from three uniform numbers.
    std::mt19937 rng(seed * 0x9E3779B9u ^ (frame + 0x7F4A7C15u) * 0x85EBCA6Bu);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double u1 = u(rng), u2 = u(rng), u3 = u(rng);
    const double twoPi = 6.283185307179586;
    double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
    double x = a * std::sin(twoPi * u2), y = a * std::cos(twoPi * u2);
    double z = b * std::sin(twoPi * u3), w = b * std::cos(twoPi * u3);
    glm::dmat3 m;
    m[0] = glm::dvec3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y));
    m[1] = glm::dvec3(2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x));
    m[2] = glm::dvec3(2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
    return glm::mat3(m);
}

RaySet makeRaySet(const DdgiDesc& desc, std::uint32_t seed, std::uint32_t frame) {
    RaySet set;
    set.fixedRays = desc.fixedRayCount();
    set.blendRays = desc.rays;
    set.rotation = randomRotation(seed, frame);
    set.directions.reserve(std::size_t(set.stride()));
    for (int i = 0; i < set.fixedRays; ++i) set.directions.push_back(sphericalFibonacci(i, set.fixedRays));
    for (int i = 0; i < set.blendRays; ++i)
        set.directions.push_back(glm::normalize(set.rotation * sphericalFibonacci(i, set.blendRays)));
    return set;
}

void traceProbes(const RayTracer& tracer, const ProbeField& field, const RaySet& rays, ProbeTrace& trace,
                 HitCache* group, bool blendRays) {
    const Scene& scene = tracer.scene();
    // Emission table entries per emissive material, and which meshes count as emitters.
    trace.emission.assign(1, glm::vec3(0.0f));
    Emitters emitters;
    emitters.material.assign(scene.materials.size(), 0);
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        if (!scene.materials[m].isEmissive()) continue;
        if (trace.emission.size() == 0xFFFF) throw InputError("DDGI: more than 65534 emissive materials");
        emitters.material[m] = std::uint16_t(trace.emission.size());
        trace.emission.push_back(scene.materials[m].emission);
    }
    for (const Mesh& mesh : scene.meshes) emitters.mesh.push_back(!mesh.isQuadLightGeometry());

    const int probes = field.probeCount();
    trace.stride = rays.stride();
    // Every traced ray writes its whole surfel below, and readers only look at traced rays, so
    // the buffer is kept between frames rather than cleared (clearing cost 10-20 % of a trace).
    trace.surfels.resize(std::size_t(probes) * std::size_t(trace.stride));
    trace.origins.resize(std::size_t(probes));
    for (int p = 0; p < probes; ++p) trace.origins[std::size_t(p)] = field.probePosition(p);
    trace.blendRaysTraced = blendRays;
    // The rays a probe's work asks for, as traced here.
    auto tracedRays = [&](ProbeWork w) {
        return w == ProbeWork::Full && blendRays ? trace.stride : w == ProbeWork::None ? 0 : rays.fixedRays;
    };
    std::int64_t traced = 0;
    for (int p = 0; p < probes; ++p) traced += tracedRays(trace.work[std::size_t(p)]);
    trace.raysTraced = traced;

    // Each blend ray stands for 1 / blendRays of the sphere: its albedo is the texture averaged
    // over that cone's footprint, not a point sample (no aliasing, and coarse mips stay cached).
    const float spread = coneSpreadForRays(rays.blendRays);
    // One task per (probe, ray chunk) keeps both cores busy on small grids too.
    const int chunk = 64;
    const int chunksPerProbe = (trace.stride + chunk - 1) / chunk;
    tbb::parallel_for(tbb::blocked_range<int>(0, probes * chunksPerProbe), [&](const tbb::blocked_range<int>& r) {
        std::optional<HitCache::Writer> writer;
        if (group) writer.emplace(*group);
        RawHit hits[chunk];
        const TriangleSurface* surfaces[chunk];
        for (int task = r.begin(); task != r.end(); ++task) {
            int p = task / chunksPerProbe;
            const int end = tracedRays(trace.work[std::size_t(p)]);
            int first = (task % chunksPerProbe) * chunk;
            int last = std::min(end, first + chunk);
            if (first >= last) continue;
            const glm::vec3 origin = trace.origins[std::size_t(p)];
            // The whole chunk is traced before any surfel is built, so that the surfels' loads
            // overlap one another instead of stalling each traversal.
            tracer.traceFan(origin, &rays.directions[std::size_t(first)], last - first, hits, surfaces);
            for (int i = first; i < last; ++i) {
                const glm::vec3 d = rays.directions[std::size_t(i)];
                ProbeSurfel& s = trace.surfels[std::size_t(p) * std::size_t(trace.stride) + std::size_t(i)];
                const bool blend = i >= rays.fixedRays;
                glm::vec3 position;
                toSurfel(tracer, emitters, hits[i - first], surfaces[i - first], origin, d, blend ? spread : -1.0f, s,
                         &position);
                if (writer && blend) {
                    const std::size_t h = std::size_t(p) * std::size_t(rays.blendRays) + std::size_t(i - rays.fixedRays);
                    if (shadedHit(s)) writer->add(h, position, s.normal);
                    else writer->skip(h);
                }
            }
        }
    });
}

}  // namespace voxgi
