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

// One probe ray's hit, 24 bytes: every shading pass streams these, so the position is not
// stored (ProbeTrace::position rebuilds it from the ray) and the albedo is 16-bit fixed point.
// Classification rays (the first fixedRays of a probe) are never shaded: their albedo is 0.
struct ProbeSurfel {
    float distance = kMissDistance;  // signed: negative for a backface hit
    glm::vec3 normal{0.0f};          // facing the probe; zero for misses and backfaces
    std::uint16_t albedo[3] = {0, 0, 0};  // (1 - metallic)(1 - specular) albedo in [0, 1], unorm16
    std::uint16_t emitter = 0;       // index into ProbeTrace::emission (0: none)

    glm::vec3 diffuseAlbedo() const {
        return glm::vec3(float(albedo[0]), float(albedo[1]), float(albedo[2])) * (1.0f / 65535.0f);
    }
    void setDiffuseAlbedo(glm::vec3 a) {
        for (int c = 0; c < 3; ++c) albedo[c] = std::uint16_t(glm::clamp(a[c], 0.0f, 1.0f) * 65535.0f + 0.5f);
    }
    bool dark() const { return (albedo[0] | albedo[1] | albedo[2]) == 0; }
};

// A front-face hit with some diffuse albedo: it reflects light toward its probe, so shading
// computes it (and the hit cache may group it).
inline bool shadedHit(const ProbeSurfel& s) { return !(s.distance < 0.0f) && s.distance < kMissDistance && !s.dark(); }

struct ProbeTrace {
    int stride = 0;                 // surfels per probe (RaySet::stride)
    std::vector<ProbeWork> work;    // per probe
    std::vector<glm::vec3> origins;      // per probe: where its rays started this frame
    std::vector<ProbeSurfel> surfels;    // probe * stride + ray
    // Front-face emission of the meshes that are not analytic lights, per emissive material
    // (entry 0 is none), what ProbeSurfel::emitter indexes.
    std::vector<glm::vec3> emission;
    std::int64_t raysTraced = 0;
    // False when only the fixed rays were traced here (the blend rays went to the GPU: ddgi.trace
    // = volume): the blend rays' surfels are then stale and nothing reads them.
    bool blendRaysTraced = true;

    const ProbeSurfel& at(int probe, int ray) const { return surfels[std::size_t(probe) * std::size_t(stride) + std::size_t(ray)]; }
    // The hit point of ray `ray` (of the RaySet traced) of `probe`; meaningless for misses.
    glm::vec3 position(const RaySet& rays, int probe, int ray) const {
        return origins[std::size_t(probe)] + std::abs(at(probe, ray).distance) * rays.directions[std::size_t(ray)];
    }
};

// Traces the rays `work` asks for from every probe's (relocated) position; without
// `blendRays`, only the fixed rays even of the probes that blend (their blend rays are traced
// elsewhere: ProbeTrace::blendRaysTraced). With `group` (begun for probeCount * blendRays
// hits), shaded blend-ray hits are added to it as they are traced: hit probe * blendRays + ray.
void traceProbes(const RayTracer& tracer, const ProbeField& field, const RaySet& rays, ProbeTrace& trace,
                 HitCache* group = nullptr, bool blendRays = true);

}  // namespace voxgi
