#include "gi/ddgi/probe_blend.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/octahedral/octahedral.h"
#include "shaders/shared/constants.h"

namespace voxgi {

namespace {

constexpr int kLanes = 8;

// One job's rays as structure-of-arrays, padded to whole lanes with zero-weight rays, so the
// per-texel loops below run eight rays at a time (the compiler vectorizes the lane loops).
struct RayLanes {
    int count = 0;  // padded
    std::vector<float> dx, dy, dz, r, g, b, front, distance;

    void fill(const RaySet& rays, const glm::vec4* values, float maxDistance) {
        count = (rays.blendRays + kLanes - 1) / kLanes * kLanes;
        for (auto* v : {&dx, &dy, &dz, &r, &g, &b, &front, &distance}) v->assign(std::size_t(count), 0.0f);
        for (int i = 0; i < rays.blendRays; ++i) {
            const glm::vec3& d = rays.blendDirection(i);
            const glm::vec4& v = values[i];
            dx[std::size_t(i)] = d.x, dy[std::size_t(i)] = d.y, dz[std::size_t(i)] = d.z;
            // Backfaces carry no light; their distance is shortened (kBackfaceDistanceScale).
            bool isFront = v.w >= 0.0f;
            front[std::size_t(i)] = isFront ? 1.0f : 0.0f;
            r[std::size_t(i)] = isFront ? v.x : 0.0f, g[std::size_t(i)] = isFront ? v.y : 0.0f;
            b[std::size_t(i)] = isFront ? v.z : 0.0f;
            distance[std::size_t(i)] = std::min(isFront ? v.w : -kBackfaceDistanceScale * v.w, maxDistance);
        }
    }
};

float maxComponent(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

glm::vec4 blendIrradianceTexel(const BlendParams& bp, const RayLanes& rays, glm::vec3 dir, glm::vec4 previous,
                               float hysteresis) {
    float sr[kLanes] = {}, sg[kLanes] = {}, sb[kLanes] = {}, sw[kLanes] = {};
    for (int i = 0; i < rays.count; i += kLanes)
        for (int j = 0; j < kLanes; ++j) {
            std::size_t k = std::size_t(i + j);
            float c = dir.x * rays.dx[k] + dir.y * rays.dy[k] + dir.z * rays.dz[k];
            float w = std::max(0.0f, c) * rays.front[k];
            sr[j] += w * rays.r[k], sg[j] += w * rays.g[k], sb[j] += w * rays.b[k], sw[j] += w;
        }
    glm::vec3 sum(0.0f);
    float wsum = 0.0f;
    for (int j = 0; j < kLanes; ++j) sum += glm::vec3(sr[j], sg[j], sb[j]), wsum += sw[j];
    if (!(wsum > 0.0f)) return previous;  // no ray in this hemisphere: keep what we had
    // pi * (cosine-weighted mean radiance) estimates the irradiance for uniform directions.
    glm::vec3 e = glm::max(shading::kPi * sum / wsum, glm::vec3(0.0f));
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

// Weights c^exponent: by repeated squaring when the exponent is a whole number (the default
// 50), the same in shaders/ddgi/blend.comp.
glm::vec4 blendDistanceTexel(const BlendParams& bp, const RayLanes& rays, glm::vec3 dir, glm::vec4 previous,
                             float hysteresis) {
    const float e = bp.distanceExponent;
    const bool whole = e == float(int(e)) && e >= 1.0f && e <= 1024.0f;
    float sd[kLanes] = {}, sd2[kLanes] = {}, sw[kLanes] = {};
    for (int i = 0; i < rays.count; i += kLanes) {
        float base[kLanes], w[kLanes];
        for (int j = 0; j < kLanes; ++j) {
            std::size_t k = std::size_t(i + j);
            base[j] = std::max(0.0f, dir.x * rays.dx[k] + dir.y * rays.dy[k] + dir.z * rays.dz[k]);
            w[j] = 1.0f;
        }
        if (whole) {
            for (int bits = int(e); bits; bits >>= 1) {
                if (bits & 1)
                    for (int j = 0; j < kLanes; ++j) w[j] *= base[j];
                for (int j = 0; j < kLanes; ++j) base[j] *= base[j];
            }
        } else {
            for (int j = 0; j < kLanes; ++j) w[j] = base[j] > 0.0f ? std::pow(base[j], e) : 0.0f;
        }
        for (int j = 0; j < kLanes; ++j) {
            float d = rays.distance[std::size_t(i + j)];
            sd[j] += w[j] * d, sd2[j] += w[j] * d * d, sw[j] += w[j];
        }
    }
    glm::vec2 sum(0.0f);
    float wsum = 0.0f;
    for (int j = 0; j < kLanes; ++j) sum += glm::vec2(sd[j], sd2[j]), wsum += sw[j];
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

float probeHysteresis(float hysteresis, int blends) {
    if (hysteresis >= 1.0f) return blends > 0 ? 1.0f : 0.0f;  // frozen after the first data
    const float n = float(std::max(blends, 0));
    return std::min(hysteresis, n / (n + 1.0f));
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
        job.hysteresis = probeHysteresis(field.desc().hysteresis, field.probes[std::size_t(p)].blends);
        job.maxDistance = field.volumes()[std::size_t(field.volumeOf(p))].maxDistance();
        jobs.push_back(job);
    }
    return jobs;
}

void CpuBlend::blend(ProbeField& field, const RaySet& rays, const ShadedRays& shaded,
                     const std::vector<BlendJob>& jobs) {
    field.atlasesChanged();
    const BlendParams bp = BlendParams::from(field.desc());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, jobs.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        RayLanes lanes;
        for (std::size_t j = r.begin(); j != r.end(); ++j) {
            const BlendJob& job = jobs[j];
            lanes.fill(rays, &shaded.values[std::size_t(job.rayBase)], job.maxDistance);
            for (int y = 0; y < bp.irradianceTexels; ++y)
                for (int x = 0; x < bp.irradianceTexels; ++x) {
                    glm::vec4& t = field.irradiance.at(job.irradianceX + 1 + x, job.irradianceY + 1 + y);
                    t = blendIrradianceTexel(bp, lanes, oct::texelDirection(x, y, bp.irradianceTexels), t,
                                             job.hysteresis);
                }
            for (int y = 0; y < bp.distanceTexels; ++y)
                for (int x = 0; x < bp.distanceTexels; ++x) {
                    glm::vec4& t = field.distance.at(job.distanceX + 1 + x, job.distanceY + 1 + y);
                    t = blendDistanceTexel(bp, lanes, oct::texelDirection(x, y, bp.distanceTexels), t,
                                           job.hysteresis);
                }
        }
    });
}

void CpuBlend::border(ProbeField& field, const std::vector<BlendJob>& jobs) {
    field.atlasesChanged();
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
