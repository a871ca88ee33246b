#include "gi/ddgi/occlusion_probes.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/ddgi/probe_sampling.h"
#include "gi/octahedral/octahedral.h"
#include "gi/sampling/sequences.h"
#include "shaders/shared/light_model.h"

namespace voxgi {

float OcclusionProbeVisibility::visible(int light, glm::vec3 p, glm::vec3 n, glm::vec3 l, float range) const {
    if (light >= kOcclusionLights) return fallback_.visible(light, p, n, l, range);
    return glm::clamp(sampler_.occlusion(p, n)[light], 0.0f, 1.0f);
}

std::int64_t updateOcclusionProbes(const Scene& scene, const LightVisibility& shadowRays, ProbeField& field,
                                   const RaySet& rays, const ProbeTrace& trace, const std::vector<BlendJob>& jobs,
                                   std::uint32_t frame, int stride) {
    if (field.occlusion.texels.empty()) return 0;
    const int lights = std::min<int>(int(scene.lights.size()), kOcclusionLights);
    std::vector<shading::PackedLight> packed;
    for (int l = 0; l < lights; ++l) packed.push_back(shading::packLight(scene.lights[std::size_t(l)]));
    const int n = field.desc().distanceTexels;
    const float exponent = field.desc().distanceExponent;
    // The texel weights depend only on this frame's ray subset, the same for every probe:
    // tabulated once (texel x subset ray, zero where the ray points away) instead of a pow per
    // probe, texel and ray.
    const int firstRay = int(frame % std::uint32_t(stride));
    const int subset = firstRay < rays.blendRays ? (rays.blendRays - firstRay + stride - 1) / stride : 0;
    // Padded to whole lanes of eight with zero weights: the sums below run eight rays at a time.
    constexpr int kLanes = 8;
    const int padded = (subset + kLanes - 1) / kLanes * kLanes;
    std::vector<float> weights(std::size_t(n * n) * std::size_t(padded), 0.0f);
    tbb::parallel_for(0, n * n, [&](int texel) {
        glm::vec3 dir = oct::texelDirection(texel % n, texel / n, n);
        for (int k = 0; k < subset; ++k) {
            float c = std::max(0.0f, glm::dot(dir, rays.blendDirection(firstRay + k * stride)));
            if (c > 0.0f) weights[std::size_t(texel) * std::size_t(padded) + std::size_t(k)] = std::pow(c, exponent);
        }
    });
    std::atomic<std::int64_t> traced{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, jobs.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        // Per subset ray and light: mask (the ray's hit tested the light) and mask x visibility,
        // structure of arrays so the texel sums below run over all subset rays branch-free
        // (rays without a test add exact zeros).
        std::vector<float> tested(std::size_t(kOcclusionLights) * std::size_t(padded));
        std::vector<float> lit(tested.size());
        std::int64_t count = 0;
        for (std::size_t j = r.begin(); j != r.end(); ++j) {
            const BlendJob& job = jobs[j];
            std::fill(tested.begin(), tested.end(), 0.0f);
            std::fill(lit.begin(), lit.end(), 0.0f);
            for (int k = 0; k < subset; ++k) {
                const int i = firstRay + k * stride;
                const ProbeSurfel& s = trace.at(job.probe, rays.fixedRays + i);
                if (s.distance <= 0.0f || s.distance >= kMissDistance) continue;
                const glm::vec3 position = trace.position(rays, job.probe, rays.fixedRays + i);
                glm::vec2 u = r2Sequence(int(frame) * rays.blendRays + i, glm::vec2(0.5f) + 0.137f * float(job.probe % 7));
                for (int l = 0; l < lights; ++l) {
                    const shading::IncidentLight incident = shading::evaluateLight(packed[std::size_t(l)], position, u);
                    // A surface facing away says nothing about the light's visibility.
                    if (glm::dot(incident.direction, s.normal) <= 0.0f) continue;
                    std::size_t at = std::size_t(l) * std::size_t(padded) + std::size_t(k);
                    tested[at] = 1.0f;
                    lit[at] = shadowRays.visible(l, position, s.normal, incident.direction, incident.distance);
                    ++count;
                }
            }
            for (int texel = 0; texel < n * n; ++texel) {
                const float* w = &weights[std::size_t(texel) * std::size_t(padded)];
                glm::vec4& t = field.occlusion.at(job.distanceX + 1 + texel % n, job.distanceY + 1 + texel / n);
                for (int l = 0; l < lights; ++l) {
                    const float* m = &tested[std::size_t(l) * std::size_t(padded)];
                    const float* v = &lit[std::size_t(l) * std::size_t(padded)];
                    float sums[kLanes] = {}, wsums[kLanes] = {};
                    for (int k = 0; k < padded; k += kLanes)
                        for (int lane = 0; lane < kLanes; ++lane) {
                            sums[lane] += w[k + lane] * v[k + lane];
                            wsums[lane] += w[k + lane] * m[k + lane];
                        }
                    float sum = 0.0f, wsum = 0.0f;
                    for (int lane = 0; lane < kLanes; ++lane) sum += sums[lane], wsum += wsums[lane];
                    if (wsum > 0.0f) t[l] = glm::mix(sum / wsum, t[l], job.hysteresis);
                }
            }
            for (int y = 0; y < n + 2; ++y)
                for (int x = 0; x < n + 2; ++x) {
                    if (x > 0 && y > 0 && x <= n && y <= n) continue;
                    glm::ivec2 src = oct::borderSource(x, y, n);
                    field.occlusion.at(job.distanceX + x, job.distanceY + y) =
                        field.occlusion.at(job.distanceX + src.x, job.distanceY + src.y);
                }
        }
        traced += count;
    });
    return traced.load();
}

}  // namespace voxgi
