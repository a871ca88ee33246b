// Occlusion probes (seed 004, chapter 5): a second octahedral field, at the distance maps'
// resolution, holding for each probe the visibility of up to four lights at the surfaces it
// sees. Shadow rays from a rotating subset of the probe-ray hits feed it; ray shading then
// reads light visibility from it (one frame late, as in the thesis) instead of tracing a
// shadow ray per hit. Lights beyond the fourth keep their shadow rays.
#pragma once

#include <cstdint>
#include <vector>

#include "gi/ddgi/hit_shading.h"
#include "gi/ddgi/probe_blend.h"
#include "gi/ddgi/probe_sampling.h"

namespace voxgi {

inline constexpr int kOcclusionLights = 4;

class OcclusionProbeVisibility : public LightVisibility {
public:
    // `sampler` holds the previous frame's field (built once per frame).
    OcclusionProbeVisibility(const ProbeSampler& sampler, const LightVisibility& fallback)
        : sampler_(sampler), fallback_(fallback) {}
    float visible(int light, glm::vec3 p, glm::vec3 n, glm::vec3 l, float range) const override;

private:
    const ProbeSampler& sampler_;
    const LightVisibility& fallback_;
};

// Traces shadow rays from every `stride`-th blend ray's front-face hit (the subset rotates with
// the frame) and blends the visibilities into the jobs' occlusion tiles, borders included.
// Returns the number of shadow rays.
std::int64_t updateOcclusionProbes(const Scene& scene, const LightVisibility& shadowRays, ProbeField& field,
                                   const RaySet& rays, const ProbeTrace& trace, const std::vector<BlendJob>& jobs,
                                   std::uint32_t frame, int stride);

}  // namespace voxgi
