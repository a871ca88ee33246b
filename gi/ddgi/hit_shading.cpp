#include "gi/ddgi/hit_shading.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/ddgi/probe_sampling.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/sampling/sequences.h"

namespace voxgi {

namespace {
constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 1.0f / kPi;

float smoothstep(float e0, float e1, float x) {
    if (e1 <= e0) return x >= e1 ? 1.0f : 0.0f;
    float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}
}  // namespace

float ShadowRayVisibility::visible(int, glm::vec3 p, glm::vec3 n, glm::vec3 l, float range) const {
    glm::vec3 origin = p + n * offset_;
    float tMax = std::isfinite(range) ? range * (1.0f - 1e-4f) - offset_ : 1e30f;
    if (tMax <= 0.0f) return 1.0f;
    return tracer_.occluded(origin, l, 0.0f, tMax) ? 0.0f : 1.0f;
}

void lightDirection(const Light& light, glm::vec3 p, glm::vec2 quadSample, glm::vec3* l, float* range) {
    if (light.type == LightType::Directional) {
        *l = -glm::normalize(light.direction);
        *range = INFINITY;
        return;
    }
    glm::vec3 position = light.type == LightType::Quad
                             ? light.position + quadSample.x * light.edgeU + quadSample.y * light.edgeV
                             : light.position;
    glm::vec3 toLight = position - p;
    *range = glm::length(toLight);
    *l = *range > 0.0f ? toLight / *range : glm::vec3(0.0f, 1.0f, 0.0f);
}

glm::vec3 directIrradiance(const Scene& scene, const LightVisibility& visibility, glm::vec3 p, glm::vec3 n,
                           glm::vec2 quadSample) {
    glm::vec3 e(0.0f);
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        if (light.type == LightType::Directional) {
            glm::vec3 l = -glm::normalize(light.direction);
            float c = glm::dot(n, l);
            if (c > 0.0f) e += light.color * c * visibility.visible(int(i), p, n, l, INFINITY);
            continue;
        }
        glm::vec3 position = light.position;
        glm::vec3 intensity = light.color;  // W/sr
        if (light.type == LightType::Quad) {
            position = light.position + quadSample.x * light.edgeU + quadSample.y * light.edgeV;
            intensity = light.color * light.area();
        }
        glm::vec3 toLight = position - p;
        float d2 = glm::dot(toLight, toLight);
        if (!(d2 > 1e-12f)) continue;
        float d = std::sqrt(d2);
        glm::vec3 l = toLight / d;
        float c = glm::dot(n, l);
        if (c <= 0.0f) continue;
        if (light.type == LightType::Spot) {
            float cosOuter = std::cos(glm::radians(light.outerConeDegrees));
            float cosInner = std::cos(glm::radians(light.innerConeDegrees));
            intensity *= smoothstep(cosOuter, cosInner, glm::dot(-l, glm::normalize(light.direction)));
        } else if (light.type == LightType::Quad) {
            intensity *= std::max(glm::dot(light.quadNormal(), -l), 0.0f);
        }
        if (glm::max(intensity.x, glm::max(intensity.y, intensity.z)) <= 0.0f) continue;
        e += intensity * (c / d2) * visibility.visible(int(i), p, n, l, d);
    }
    return e;
}

ShadeStats shadeProbeRays(const Scene& scene, const LightVisibility& visibility, const ProbeField& previous,
                          const RaySet& rays, const ProbeTrace& trace, const std::vector<int>& probes,
                          std::uint32_t frame, ShadedRays& out) {
    const float energy = previous.desc().energyPreservation;
    const glm::vec3 sky = scene.sky.enabled ? scene.sky.radiance : glm::vec3(0.0f);
    out.raysPerJob = rays.blendRays;
    out.values.assign(probes.size() * std::size_t(rays.blendRays), glm::vec4(0.0f));
    std::atomic<std::int64_t> shadow{0};
    const std::int64_t lights = std::int64_t(scene.lights.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, probes.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        std::int64_t queries = 0;
        for (std::size_t job = r.begin(); job != r.end(); ++job) {
            int probe = probes[job];
            for (int i = 0; i < rays.blendRays; ++i) {
                const Surfel& s = trace.at(probe, rays.fixedRays + i);
                glm::vec4& o = out.values[job * std::size_t(rays.blendRays) + std::size_t(i)];
                if (s.distance >= kMissDistance) {
                    o = glm::vec4(sky, kMissDistance);
                    continue;
                }
                if (s.distance < 0.0f) {
                    o = glm::vec4(0.0f, 0.0f, 0.0f, s.distance);
                    continue;
                }
                glm::vec3 radiance = s.emission;
                if (glm::max(s.diffuseAlbedo.x, glm::max(s.diffuseAlbedo.y, s.diffuseAlbedo.z)) > 0.0f) {
                    glm::vec2 u = r2Sequence(int(frame) * rays.blendRays + i, glm::vec2(0.5f) + 0.137f * float(probe % 7));
                    glm::vec3 e = directIrradiance(scene, visibility, s.position, s.normal, u);
                    queries += lights;
                    glm::vec3 toProbe = -rays.blendDirection(i);
                    if (energy > 0.0f) e += energy * sampleIrradiance(previous, s.position, s.normal, toProbe);
                    radiance += s.diffuseAlbedo * kInvPi * e;
                }
                o = glm::vec4(radiance, s.distance);
            }
        }
        shadow += queries;
    });
    ShadeStats stats;
    stats.shadowQueries = shadow.load();
    return stats;
}

}  // namespace voxgi
