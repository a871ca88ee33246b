#include "gi/ddgi/probe_blend.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/octahedral/octahedral.h"

namespace voxgi {

namespace {
constexpr float kPi = 3.14159265358979323846f;

// c^e by repeated squaring when e is a whole number (the default 50): far cheaper than powf
// in the innermost loop, and equal to it within float rounding.
float weightPow(float c, float e) {
    if (e == float(int(e)) && e >= 1.0f && e <= 1024.0f) {
        int k = int(e);
        float result = 1.0f, base = c;
        while (k) {
            if (k & 1) result *= base;
            base *= base;
            k >>= 1;
        }
        return result;
    }
    return std::pow(c, e);
}

float maxComponent(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

glm::vec4 blendIrradianceTexel(const BlendParams& bp, const RaySet& rays, const glm::vec4* values, glm::vec3 dir,
                               glm::vec4 previous, float hysteresis) {
    glm::vec3 sum(0.0f);
    float wsum = 0.0f;
    for (int i = 0; i < rays.blendRays; ++i) {
        if (values[i].w < 0.0f) continue;  // backfaces carry no light
        float w = std::max(0.0f, glm::dot(dir, rays.blendDirection(i)));
        sum += w * glm::vec3(values[i]);
        wsum += w;
    }
    if (!(wsum > 0.0f)) return previous;  // no ray in this hemisphere: keep what we had
    // pi * (cosine-weighted mean radiance) estimates the irradiance for uniform directions.
    glm::vec3 e = glm::max(kPi * sum / wsum, glm::vec3(0.0f));
    glm::vec3 encoded = glm::pow(e, glm::vec3(1.0f / bp.irradianceGamma));
    glm::vec3 prev(previous);
    // The fast-response rules (RTXGI's) apply between the extremes: 0 takes the new value,
    // 1 freezes the probe.
    if (hysteresis > 0.0f && hysteresis < 1.0f) {
        if (maxComponent(glm::abs(prev - encoded)) > bp.irradianceThreshold) hysteresis = std::max(0.0f, hysteresis - 0.75f);
        glm::vec3 delta = encoded - prev;
        if (maxComponent(delta) > bp.brightnessThreshold) encoded = prev + delta * 0.25f;
    }
    return glm::vec4(glm::mix(encoded, prev, hysteresis), 1.0f);
}

glm::vec4 blendDistanceTexel(const BlendParams& bp, const RaySet& rays, const glm::vec4* values, glm::vec3 dir,
                             glm::vec4 previous, float hysteresis, float maxDistance) {
    glm::vec2 sum(0.0f);
    float wsum = 0.0f;
    for (int i = 0; i < rays.blendRays; ++i) {
        float c = std::max(0.0f, glm::dot(dir, rays.blendDirection(i)));
        if (c <= 0.0f) continue;
        float w = weightPow(c, bp.distanceExponent);
        float d = values[i].w < 0.0f ? -kBackfaceDistanceScale * values[i].w : values[i].w;
        d = std::min(d, maxDistance);
        sum += w * glm::vec2(d, d * d);
        wsum += w;
    }
    if (!(wsum > 0.0f)) return previous;
    glm::vec2 result = glm::mix(sum / wsum, glm::vec2(previous), hysteresis);
    return glm::vec4(result, 0.0f, 0.0f);
}
}  // namespace

BlendParams BlendParams::from(const DdgiDesc& d) {
    BlendParams p;
    p.irradianceTexels = d.irradianceTexels;
    p.distanceTexels = d.distanceTexels;
    p.distanceExponent = d.distanceExponent;
    p.irradianceGamma = d.irradianceGamma;
    p.irradianceThreshold = d.irradianceThreshold;
    p.brightnessThreshold = d.brightnessThreshold;
    return p;
}

std::vector<BlendJob> makeBlendJobs(const ProbeField& field, const std::vector<int>& probes, int raysPerJob) {
    std::vector<BlendJob> jobs;
    jobs.reserve(probes.size());
    for (std::size_t j = 0; j < probes.size(); ++j) {
        int p = probes[j];
        BlendJob job;
        job.probe = p;
        glm::ivec2 it = field.irradianceTile(p), dt = field.distanceTile(p);
        job.irradianceX = it.x;
        job.irradianceY = it.y;
        job.distanceX = dt.x;
        job.distanceY = dt.y;
        job.rayBase = int(j) * raysPerJob;
        job.hysteresis = field.probes[std::size_t(p)].fresh ? 0.0f : field.desc().hysteresis;
        job.maxDistance = field.volumes()[std::size_t(field.volumeOf(p))].maxDistance();
        jobs.push_back(job);
    }
    return jobs;
}

void CpuBlend::blend(ProbeField& field, const RaySet& rays, const ShadedRays& shaded,
                     const std::vector<BlendJob>& jobs) {
    const BlendParams bp = BlendParams::from(field.desc());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, jobs.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t j = r.begin(); j != r.end(); ++j) {
            const BlendJob& job = jobs[j];
            const glm::vec4* values = &shaded.values[std::size_t(job.rayBase)];
            for (int y = 0; y < bp.irradianceTexels; ++y)
                for (int x = 0; x < bp.irradianceTexels; ++x) {
                    glm::vec4& t = field.irradiance.at(job.irradianceX + 1 + x, job.irradianceY + 1 + y);
                    t = blendIrradianceTexel(bp, rays, values, oct::texelDirection(x, y, bp.irradianceTexels), t,
                                             job.hysteresis);
                }
            for (int y = 0; y < bp.distanceTexels; ++y)
                for (int x = 0; x < bp.distanceTexels; ++x) {
                    glm::vec4& t = field.distance.at(job.distanceX + 1 + x, job.distanceY + 1 + y);
                    t = blendDistanceTexel(bp, rays, values, oct::texelDirection(x, y, bp.distanceTexels), t,
                                           job.hysteresis, job.maxDistance);
                }
        }
    });
}

void CpuBlend::border(ProbeField& field, const std::vector<BlendJob>& jobs) {
    const int ni = field.desc().irradianceTexels, nd = field.desc().distanceTexels;
    auto refresh = [](Atlas& atlas, int ox, int oy, int n) {
        for (int y = 0; y < n + 2; ++y)
            for (int x = 0; x < n + 2; ++x) {
                if (x > 0 && y > 0 && x <= n && y <= n) continue;
                glm::ivec2 s = oct::borderSource(x, y, n);
                atlas.at(ox + x, oy + y) = atlas.at(ox + s.x, oy + s.y);
            }
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, jobs.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t j = r.begin(); j != r.end(); ++j) {
            refresh(field.irradiance, jobs[j].irradianceX, jobs[j].irradianceY, ni);
            refresh(field.distance, jobs[j].distanceX, jobs[j].distanceY, nd);
        }
    });
}

}  // namespace voxgi
