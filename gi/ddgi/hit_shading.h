// Radiance leaving each probe-ray hit toward its probe: emission, direct light (all light types,
// physical units like the rasterizer), the sky's light (ProbeSky) and the previous frame's probe
// irradiance (infinite bounces) times the energy-preservation factor, all over a diffuse
// (Lambert) lobe.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "gi/ddgi/probe_rays.h"
#include "shaders/ddgi/limits.h"

namespace voxgi {

class RayTracer;
class SkyVolume;

// Where the probes find the sky. Alone (tests, benchmarks) the rays that miss bring the sky's
// radiance, so the field holds the sky's direct light as well as its bounce. In a frame whose
// plan lights every surface with the sky-lighting volume (the sky_light pass), the field must
// hold only light that bounced, as the path tracer's indirect layer does: misses bring nothing
// and hits are lit by the same volume, so the sky's light still bounces.
struct ProbeSky {
    bool atMisses = true;
    const SkyVolume* volume = nullptr;  // hits add its irradiance; null: none
};

// Visibility of the lights seen from surface points; shadow rays by default. The occlusion-probe
// mode plugs in here.
struct LightVisibility {
    virtual ~LightVisibility() = default;
    // 1 when `light` reaches p along unit l over distance `range` (infinite for the sun).
    virtual float visible(int light, glm::vec3 p, glm::vec3 n, glm::vec3 l, float range) const = 0;
};

class ShadowRayVisibility : public LightVisibility {
public:
    explicit ShadowRayVisibility(const RayTracer& tracer, float offset) : tracer_(tracer), offset_(offset) {}
    float visible(int light, glm::vec3 p, glm::vec3 n, glm::vec3 l, float range) const override;

private:
    const RayTracer& tracer_;
    float offset_;
};

// Per blend job ray: rgb = radiance toward the probe (W/(m^2 sr)), a = signed hit distance.
struct ShadedRays {
    int raysPerJob = 0;
    std::vector<glm::vec4> values;  // job * raysPerJob + ray
};

struct ShadeStats {
    std::int64_t shadowQueries = 0;  // light-visibility tests (shadow rays or occlusion lookups)
    std::int64_t cacheGroups = 0;    // hit-cache groups
    std::int64_t groupsEvaluated = 0;  // of those, evaluated this frame (the rest re-used last frame's)
    std::int64_t cachedHits = 0;     // hits that took their probe irradiance from a group
    double groupsMs = 0.0;           // evaluating the groups (gathers, shared light tests)
    double hitsMs = 0.0;             // shading every hit
};

class HitCache;
class ProbeSampler;

// The points on quad lights that blend ray `ray` of `probe` uses in `frame`: entry
// (probe % kQuadSampleSets) * blendRays + ray, R2 points offset per residue, so neighbouring
// probes see different points and one table serves every probe (empty without quad lights).
inline constexpr int kQuadSampleSets = kDdgiQuadSampleSets;
std::vector<glm::vec2> quadLightSamples(const Scene& scene, int blendRays, std::uint32_t frame);
bool hasQuadLights(const Scene& scene);
// The first point of row `residue` of that table; its ray i is fract(start + i * r2Step()),
// which the GPU evaluates from these seven points instead of uploading the table.
glm::vec2 quadSampleStart(int residue, int blendRays, std::uint32_t frame);

// Whether shading with `desc` reads a hit cache (its mode is on and there is something to
// share: the probe gather, or light visibility in the `all` mode).
bool hitCacheUsed(const DdgiDesc& desc, const Scene& scene);
// The hit-cache cell of a field: its smallest probe spacing over hit_cache_cells.
float hitCacheCellSize(const ProbeField& field);
// Groups the shaded blend-ray hits of every probe `trace` traced in full (hit
// probe * blendRays + ray), for callers that did not group while tracing (traceProbes can).
void groupProbeHits(HitCache& cache, const ProbeField& field, const RaySet& rays, const ProbeTrace& trace);

// Per-frame buffers of shadeProbeRays, kept by the caller so that their memory is reused
// (fresh ones every frame cost page faults on each first touch).
struct ShadeWorkspace {
    std::vector<glm::vec4> groupValues;
    // Last frame's, for cells that are not due for evaluation (hit_cache_refresh).
    std::vector<glm::vec4> previousValues;
    int previousStride = 0;
    // The lights those values saw: a light that moved or changed re-evaluates every group.
    std::vector<float> previousLights;
    std::vector<std::uint32_t> cage, start, order, due;
};

// Shades the blend rays of `probes` (the probes that blend this frame) against the previous
// frame's field (`previous`). `grouped` holds this frame's hits grouped (traceProbes with a
// cache, or groupProbeHits); it is read when hitCacheUsed() and may be null otherwise.
ShadeStats shadeProbeRays(const Scene& scene, const LightVisibility& visibility, const ProbeSampler& previous,
                          const RaySet& rays, const ProbeTrace& trace, const std::vector<int>& probes,
                          std::uint32_t frame, const HitCache* grouped, ShadedRays& out,
                          ShadeWorkspace* workspace = nullptr, const ProbeSky& sky = {});

}  // namespace voxgi
