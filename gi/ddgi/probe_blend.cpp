#include "gi/ddgi/probe_blend.h"

#include "shaders/shared/probe_schedule.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/octahedral/octahedral.h"
#include "shaders/shared/constants.h"

// The helpers taking or returning 32-byte vectors are always inlined, so the warning about
// their calling convention concerns no real call.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace voxgi {

namespace {

constexpr int kLanes = 8;

float maxComponent(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

#if defined(__GNUC__)
#define VOXGI_BLEND_INLINE inline __attribute__((always_inline))
#else
#define VOXGI_BLEND_INLINE inline
#endif

// Eight texels per vector (GCC/Clang vector extensions: one source, built below for baseline
// x86-64 as two SSE halves and for AVX2 + FMA).
typedef float Vec8 __attribute__((vector_size(32)));
static_assert(kLanes == 8, "Vec8 holds kLanes floats");

VOXGI_BLEND_INLINE Vec8 load8(const float* p) {
    Vec8 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
VOXGI_BLEND_INLINE void store8(float* p, Vec8 v) { std::memcpy(p, &v, sizeof v); }
VOXGI_BLEND_INLINE Vec8 splat8(float x) { return Vec8{x, x, x, x, x, x, x, x}; }

// Every probe of a frame shoots the same directions (RaySet), so the weight of each
// (ray, texel) pair is the same for all of them: the tables hold, per ray, the vectors of eight
// texels it weighs in (and their weights), built once per blend; a probe then only sums its
// rays' radiance or distances into the texels those entries name.
struct WeightTable {
    int texels = 0, padded = 0;          // interior texels of a tile, padded to whole vectors
    std::vector<int> first;              // per ray: its first entry (and first[rays] = the end)
    std::vector<int> vectorOf;           // per entry: texel index / kLanes
    std::vector<float> weights;          // per entry: kLanes weights
    std::vector<float> weightSums;       // per texel: the sum over every ray (distance only)

    // Irradiance: the clamped cosine. Distance: cosine^exponent, by repeated squaring for
    // whole exponents (as shaders/ddgi/blend.comp), and a ray whose cosine to a texel is below
    // cut = (largest cosine of any ray to that texel) * (1e-7 / rays)^(1 / exponent) weighs less
    // than 1e-7 / rays of the texel's largest weight: all such rays together move the texel's
    // weighted mean by less than 1e-7 of itself, so vectors whose every weight is below the cut
    // are left out (at the default exponent 50 and 256 rays, about three in four).
    WeightTable(const RaySet& rays, int interior, bool distance, float exponent)
        : texels(interior * interior), padded((texels + kLanes - 1) / kLanes * kLanes) {
        const int n = rays.blendRays;
        std::vector<float> cosines(std::size_t(n) * std::size_t(padded), 0.0f), cut(std::size_t(padded), 0.0f);
        for (int t = 0; t < texels; ++t) {
            const glm::vec3 dir = oct::texelDirection(t % interior, t / interior, interior);
            for (int k = 0; k < n; ++k) {
                const float c = glm::dot(dir, rays.blendDirection(k));
                cosines[std::size_t(k) * std::size_t(padded) + std::size_t(t)] = c;
                cut[std::size_t(t)] = std::max(cut[std::size_t(t)], c);
            }
        }
        const bool whole = exponent == float(int(exponent)) && exponent >= 1.0f && exponent <= 1024.0f;
        const float ratio = distance ? std::pow(1e-7f / float(std::max(n, 1)), 1.0f / exponent) : 0.0f;
        for (float& c : cut) c *= ratio;
        if (distance) weightSums.assign(std::size_t(padded), 0.0f);
        first.push_back(0);
        for (int k = 0; k < n; ++k) {
            for (int i = 0; i < padded; i += kLanes) {
                float w[kLanes];
                bool any = false;
                for (int j = 0; j < kLanes; ++j) {
                    const float c = cosines[std::size_t(k) * std::size_t(padded) + std::size_t(i + j)];
                    const float base = std::max(c, 0.0f);
                    any = any || (distance ? c > cut[std::size_t(i + j)] : c > 0.0f);
                    if (!distance) {
                        w[j] = base;
                    } else if (whole) {
                        float b = base, p = 1.0f;
                        for (int bits = int(exponent); bits; bits >>= 1) {
                            if (bits & 1) p *= b;
                            b *= b;
                        }
                        w[j] = p;
                    } else {
                        w[j] = base > 0.0f ? std::pow(base, exponent) : 0.0f;
                    }
                }
                if (!any) continue;
                vectorOf.push_back(i / kLanes);
                weights.insert(weights.end(), w, w + kLanes);
                if (distance)
                    for (int j = 0; j < kLanes; ++j) weightSums[std::size_t(i + j)] += w[j];
            }
            first.push_back(int(vectorOf.size()));
        }
    }
};

// One thread's per-texel sums, reused across jobs: irradiance (r, g, b, weight) and distance
// moments (d, d^2).
struct TexelSums {
    std::vector<float> r, g, b, w, d, d2;
};

// A probe's shaded rays (ShadedRays values) into the per-texel sums. Backfaces carry no light
// and their distance is shortened (kBackfaceDistanceScale).
VOXGI_BLEND_INLINE void sumJob(const WeightTable& irradiance, const WeightTable& distance, const glm::vec4* values,
                               float maxDistance, TexelSums& s) {
    for (auto* v : {&s.r, &s.g, &s.b, &s.w}) v->assign(std::size_t(irradiance.padded), 0.0f);
    for (auto* v : {&s.d, &s.d2}) v->assign(std::size_t(distance.padded), 0.0f);
    const int n = int(irradiance.first.size()) - 1;
    for (int k = 0; k < n; ++k) {
        const glm::vec4& v = values[k];
        const bool front = v.w >= 0.0f;
        const float dist = std::min(front ? v.w : -kBackfaceDistanceScale * v.w, maxDistance);
        const Vec8 d = splat8(dist), dd = splat8(dist * dist);
        for (int e = distance.first[std::size_t(k)]; e < distance.first[std::size_t(k) + 1]; ++e) {
            const Vec8 w = load8(&distance.weights[std::size_t(e) * kLanes]);
            const std::size_t i = std::size_t(distance.vectorOf[std::size_t(e)]) * kLanes;
            store8(&s.d[i], load8(&s.d[i]) + w * d);
            store8(&s.d2[i], load8(&s.d2[i]) + w * dd);
        }
        if (!front) continue;
        const Vec8 r = splat8(v.x), g = splat8(v.y), b = splat8(v.z);
        for (int e = irradiance.first[std::size_t(k)]; e < irradiance.first[std::size_t(k) + 1]; ++e) {
            const Vec8 w = load8(&irradiance.weights[std::size_t(e) * kLanes]);
            const std::size_t i = std::size_t(irradiance.vectorOf[std::size_t(e)]) * kLanes;
            store8(&s.r[i], load8(&s.r[i]) + w * r);
            store8(&s.g[i], load8(&s.g[i]) + w * g);
            store8(&s.b[i], load8(&s.b[i]) + w * b);
            store8(&s.w[i], load8(&s.w[i]) + w);
        }
    }
}

void sumJobBaseline(const WeightTable& i, const WeightTable& d, const glm::vec4* values, float maxDistance, TexelSums& s) {
    sumJob(i, d, values, maxDistance, s);
}

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target("avx2,fma"))) void sumJobAvx2(const WeightTable& i, const WeightTable& d, const glm::vec4* values,
                                                     float maxDistance, TexelSums& s) {
    sumJob(i, d, values, maxDistance, s);
}
bool avx2Available() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }
#endif

glm::vec4 finishIrradiance(const BlendParams& bp, glm::vec3 sum, float wsum, glm::vec4 previous, float hysteresis) {
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

glm::vec4 finishDistance(glm::vec2 sum, float wsum, glm::vec4 previous, float hysteresis) {
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

float probeHysteresis(float hysteresis, int blends) { return shading::probeHysteresis(hysteresis, blends); }

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
    const WeightTable irradiance(rays, bp.irradianceTexels, false, 1.0f);
    const WeightTable distance(rays, bp.distanceTexels, true, bp.distanceExponent);
    auto sum = sumJobBaseline;
#if defined(__x86_64__) && defined(__GNUC__)
    if (avx2Available()) sum = sumJobAvx2;
#endif
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, jobs.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        TexelSums sums;
        for (std::size_t j = r.begin(); j != r.end(); ++j) {
            const BlendJob& job = jobs[j];
            sum(irradiance, distance, &shaded.values[std::size_t(job.rayBase)], job.maxDistance, sums);
            for (int t = 0; t < irradiance.texels; ++t) {
                const std::size_t T = std::size_t(t);
                glm::vec4& texel = field.irradiance.at(job.irradianceX + 1 + t % bp.irradianceTexels,
                                                       job.irradianceY + 1 + t / bp.irradianceTexels);
                texel = finishIrradiance(bp, glm::vec3(sums.r[T], sums.g[T], sums.b[T]), sums.w[T], texel, job.hysteresis);
            }
            for (int t = 0; t < distance.texels; ++t) {
                const std::size_t T = std::size_t(t);
                glm::vec4& texel = field.distance.at(job.distanceX + 1 + t % bp.distanceTexels,
                                                     job.distanceY + 1 + t / bp.distanceTexels);
                texel = finishDistance(glm::vec2(sums.d[T], sums.d2[T]), distance.weightSums[T], texel, job.hysteresis);
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
