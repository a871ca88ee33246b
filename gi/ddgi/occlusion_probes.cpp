#include "gi/ddgi/occlusion_probes.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/ddgi/probe_sampling.h"
#include "gi/octahedral/octahedral.h"
#include "gi/sampling/sequences.h"

namespace voxgi {

float OcclusionProbeVisibility::visible(int light, glm::vec3 p, glm::vec3 n, glm::vec3 l, float range) const {
    if (light >= kOcclusionLights) return fallback_.visible(light, p, n, l, range);
    return glm::clamp(sampleOcclusion(field_, p, n)[light], 0.0f, 1.0f);
}

std::int64_t updateOcclusionProbes(const Scene& scene, const LightVisibility& shadowRays, ProbeField& field,
                                   const RaySet& rays, const ProbeTrace& trace, const std::vector<BlendJob>& jobs,
                                   std::uint32_t frame, int stride) {
    if (field.occlusion.texels.empty()) return 0;
    const int lights = std::min<int>(int(scene.lights.size()), kOcclusionLights);
    const int n = field.desc().distanceTexels;
    const float exponent = field.desc().distanceExponent;
    std::atomic<std::int64_t> traced{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, jobs.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        std::vector<int> used;
        std::vector<glm::vec4> vis, mask;
        std::int64_t count = 0;
        for (std::size_t j = r.begin(); j != r.end(); ++j) {
            const BlendJob& job = jobs[j];
            used.clear();
            vis.clear();
            mask.clear();
            for (int i = int(frame % std::uint32_t(stride)); i < rays.blendRays; i += stride) {
                const Surfel& s = trace.at(job.probe, rays.fixedRays + i);
                if (s.distance <= 0.0f || s.distance >= kMissDistance) continue;
                glm::vec4 v(0.0f), m(0.0f);
                glm::vec2 u = r2Sequence(int(frame) * rays.blendRays + i, glm::vec2(0.5f) + 0.137f * float(job.probe % 7));
                for (int k = 0; k < lights; ++k) {
                    glm::vec3 l;
                    float range;
                    lightDirection(scene.lights[std::size_t(k)], s.position, u, &l, &range);
                    // A surface facing away says nothing about the light's visibility.
                    if (glm::dot(l, s.normal) <= 0.0f) continue;
                    v[k] = shadowRays.visible(k, s.position, s.normal, l, range);
                    m[k] = 1.0f;
                    ++count;
                }
                used.push_back(i);
                vis.push_back(v);
                mask.push_back(m);
            }
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    glm::vec3 dir = oct::texelDirection(x, y, n);
                    glm::vec4 sum(0.0f), wsum(0.0f);
                    for (std::size_t k = 0; k < used.size(); ++k) {
                        float c = std::max(0.0f, glm::dot(dir, rays.blendDirection(used[k])));
                        if (c <= 0.0f) continue;
                        float w = std::pow(c, exponent);
                        sum += w * mask[k] * vis[k];
                        wsum += w * mask[k];
                    }
                    glm::vec4& t = field.occlusion.at(job.distanceX + 1 + x, job.distanceY + 1 + y);
                    for (int k = 0; k < 4; ++k)
                        if (wsum[k] > 0.0f) t[k] = glm::mix(sum[k] / wsum[k], t[k], job.hysteresis);
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
