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

// A probe's hysteresis after `blends` earlier blends: min(hysteresis, blends / (blends + 1)).
// With weight n / (n + 1) on the previous value the n + 1 first blends are their plain mean
// (the probe converges as fast as its rays allow), and from n = h / (1 - h) (32 blends at 0.97)
// on, the exponential mean of ddgi.hysteresis smooths the rotated rays' noise. Before, a new
// probe took its first rays whole and then 3 % of each blend, so its irradiance rose for
// hundreds of frames toward the answer; seed 004 and RTXGI leave that start to the user.
// Hysteresis 1 still freezes a probe after its first data.
float probeHysteresis(float hysteresis, int blends);

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

    // A backend that runs the whole update itself, the probe states included (DDGI's
    // ddgi.trace = volume on the GPU): it schedules the probes, traces and shades their rays,
    // blends, borders, relocates and classifies them, with `rays`' directions for `frame`, and
    // returns what it counted and timed. field.probes and the atlases are then its own until
    // syncToCpu.
    virtual bool updatesProbes() const { return false; }
    struct UpdateReport {
        int blended = 0, fixedOnly = 0;  // probes that traced every ray / only the fixed ones
        int active = 0, sleeping = 0, off = 0;
        // Wall time of each stage, the schedule counted with classification.
        double traceMs = 0.0, blendMs = 0.0, borderMs = 0.0, classifyMs = 0.0;
        // The update (its frame number) the counts above describe: a GPU reads them back later
        // (DdgiGpu::updateProbes); -1 while none has come back.
        std::int64_t countedFrame = -1;
    };
    virtual UpdateReport updateProbes(ProbeField&, const RaySet&, std::uint32_t /*frame*/) { return {}; }
    // A backend that keeps the newest atlases (and, with updatesProbes, the probe records) to
    // itself brings field.irradiance, field.distance and field.probes up to date here; callers
    // do so before any CPU read or write of them.
    virtual void syncToCpu(ProbeField&) {}
};

class CpuBlend : public BlendBackend {
public:
    void blend(ProbeField& field, const RaySet& rays, const ShadedRays& shaded,
               const std::vector<BlendJob>& jobs) override;
    void border(ProbeField& field, const std::vector<BlendJob>& jobs) override;
};

}  // namespace voxgi
