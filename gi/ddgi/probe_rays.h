// Probe rays: spherical Fibonacci directions (rotated randomly each frame for blending, a
// fixed unrotated set for classification), traced with Embree across TBB threads into a
// surfel buffer.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gi/ddgi/probe_field.h"

namespace voxgi {

class HitCache;
class RayTracer;

// Stored distance of a ray that left the scene.
inline constexpr float kMissDistance = 1e30f;

struct RaySet {
    int fixedRays = 0;
    int blendRays = 0;
    glm::mat3 rotation{1.0f};
    std::vector<glm::vec3> directions;  // fixed rays first, then the rotated blend rays

    int stride() const { return fixedRays + blendRays; }
    const glm::vec3& blendDirection(int i) const { return directions[std::size_t(fixedRays + i)]; }
};

// A uniformly random rotation for (seed, frame), the same on every machine.
glm::mat3 randomRotation(std::uint32_t seed, std::uint32_t frame);
RaySet makeRaySet(const DdgiDesc& desc, std::uint32_t seed, std::uint32_t frame);

enum class ProbeWork : std::uint8_t {
    None,       // not traced this frame
    FixedOnly,  // only the classification rays (sleeping or off probes between updates)
    Full,       // classification and blend rays; the probe blends this frame
};

// Classification rays (the first fixedRays of a probe) are never shaded: their albedo is 0.
struct ProbeSurfel {
    glm::vec3 position{0.0f};
    float distance = kMissDistance;  // signed: negative for a backface hit
    glm::vec3 normal{0.0f};          // facing the probe; zero for misses and backfaces
    glm::vec3 diffuseAlbedo{0.0f};   // (1 - metallic)(1 - specular) albedo
    glm::vec3 emission{0.0f};        // front-face emission of meshes that are not analytic lights
};

// A front-face hit with some diffuse albedo: it reflects light toward its probe, so shading
// computes it (and the hit cache may group it).
inline bool shadedHit(const ProbeSurfel& s) {
    return !(s.distance < 0.0f) && s.distance < kMissDistance &&
           glm::max(s.diffuseAlbedo.x, glm::max(s.diffuseAlbedo.y, s.diffuseAlbedo.z)) > 0.0f;
}

struct ProbeTrace {
    int stride = 0;                 // surfels per probe (RaySet::stride)
    std::vector<ProbeWork> work;    // per probe
    std::vector<ProbeSurfel> surfels;    // probe * stride + ray
    std::int64_t raysTraced = 0;

    const ProbeSurfel& at(int probe, int ray) const { return surfels[std::size_t(probe) * std::size_t(stride) + std::size_t(ray)]; }
};

// Traces the rays `work` asks for from every probe's (relocated) position. With `group` (begun
// for probeCount * blendRays hits), shaded blend-ray hits are added to it as they are traced:
// hit probe * blendRays + ray.
void traceProbes(const RayTracer& tracer, const ProbeField& field, const RaySet& rays, ProbeTrace& trace,
                 HitCache* group = nullptr);

}  // namespace voxgi
