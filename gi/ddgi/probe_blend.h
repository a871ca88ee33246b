// The probe update: each interior texel of a probe's irradiance and distance tiles blends the
// probe's shaded rays (cosine weights for irradiance, cosine^exponent for distance moments)
// into its previous value with hysteresis; then the one-texel borders are refreshed.
// The CPU reference of shaders/ddgi/blend.comp and border.comp; the GL path implements the
// same BlendBackend (gi/ddgi/ddgi_gpu.h).
#pragma once

#include <vector>

#include "gi/ddgi/hit_shading.h"
#include "gi/ddgi/probe_field.h"
#include "gi/ddgi/probe_rays.h"

namespace voxgi {

// One probe to blend; the layout matches the std430 struct in shaders/ddgi/blend_common.glsl.
struct BlendJob {
    int probe = 0;
    int irradianceX = 0, irradianceY = 0;  // tile origins in texels (border included)
    int distanceX = 0, distanceY = 0;
    int rayBase = 0;                       // first ray of this job in ShadedRays::values
    float hysteresis = 0.0f;               // 0 = take the new value (fresh probes)
    float maxDistance = 0.0f;
};
static_assert(sizeof(BlendJob) == 32, "BlendJob must match the GLSL std430 layout");

std::vector<BlendJob> makeBlendJobs(const ProbeField& field, const std::vector<int>& probes, int raysPerJob);

// Blending constants shared by both back ends.
struct BlendParams {
    int irradianceTexels = 8;
    int distanceTexels = 16;
    float distanceExponent = 50.0f;
    float irradianceGamma = 5.0f;
    float irradianceThreshold = 0.25f;
    float brightnessThreshold = 0.1f;
    static BlendParams from(const DdgiDesc& desc);
};

// Backface hits shorten the stored distance to a fifth of the hit distance (as RTXGI does) so a
// probe behind a wall reads as occluded rather than open.
inline constexpr float kBackfaceDistanceScale = 0.2f;

class BlendBackend {
public:
    virtual ~BlendBackend() = default;
    // Blends and refreshes borders of the jobs' tiles in field.irradiance / field.distance.
    virtual void blend(ProbeField& field, const RaySet& rays, const ShadedRays& shaded,
                       const std::vector<BlendJob>& jobs) = 0;
    virtual void border(ProbeField& field, const std::vector<BlendJob>& jobs) = 0;
};

class CpuBlend : public BlendBackend {
public:
    void blend(ProbeField& field, const RaySet& rays, const ShadedRays& shaded,
               const std::vector<BlendJob>& jobs) override;
    void border(ProbeField& field, const std::vector<BlendJob>& jobs) override;
};

}  // namespace voxgi
