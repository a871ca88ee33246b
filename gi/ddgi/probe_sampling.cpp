#include "gi/ddgi/probe_sampling.h"

#include <algorithm>
#include <cmath>

#include "gi/octahedral/octahedral.h"

namespace voxgi {

float chebyshevVisibility(float r, float mean, float meanSquare) {
    if (r <= mean) return 1.0f;
    float variance = std::max(meanSquare - mean * mean, 0.0f);
    if (variance <= 0.0f) return 0.0f;
    float d = r - mean;
    float p = variance / (variance + d * d);
    // Cubed to sharpen the bound (as RTXGI does); it is loose by construction.
    return p * p * p;
}

float volumeBlendWeight(const ProbeVolume& v, glm::vec3 p) {
    glm::vec3 x = (p - v.origin) / v.spacing;
    float w = 1.0f;
    for (int a = 0; a < 3; ++a) {
        if (v.counts[a] < 2) continue;
        float last = float(v.counts[a] - 1);
        w *= std::clamp(x[a], 0.0f, 1.0f) * std::clamp(last - x[a], 0.0f, 1.0f);
    }
    return w;
}

namespace {
// x^(gamma/2) with a fast path for the default gamma 5 (x^2.5 = x^2 sqrt x); same values as pow.
glm::vec3 decodeHalf(glm::vec3 x, float halfGamma) {
    if (halfGamma == 2.5f) return x * x * glm::sqrt(x);
    if (halfGamma == 1.0f) return x;
    return glm::pow(x, glm::vec3(halfGamma));
}
}  // namespace

namespace {

// The weighted cage gather shared by irradiance and occlusion lookups: `lookup(tile, dir)`
// returns the value of the probe whose tile index is given, `dir` being the unit
// direction from the probe to the (biased) point.
template <typename Lookup>
glm::vec4 gatherCage(const ProbeField& field, int vi, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer, float* weightSum,
                     Lookup&& lookup) {
    const DdgiDesc& desc = field.desc();
    const ProbeVolume& v = field.volumes()[std::size_t(vi)];
    glm::vec3 q = p + (n * desc.normalBias + toViewer * desc.viewBias) * v.minSpacing();
    glm::vec3 rel = (q - v.origin) / v.spacing;
    glm::ivec3 base = glm::clamp(glm::ivec3(glm::floor(rel)), glm::ivec3(0), glm::max(v.counts - 2, glm::ivec3(0)));
    glm::vec3 alpha = glm::clamp(rel - glm::vec3(base), 0.0f, 1.0f);
    for (int a = 0; a < 3; ++a)
        if (v.counts[a] < 2) alpha[a] = 0.0f;

    const int nd = desc.distanceTexels;
    glm::vec4 sum(0.0f);
    float wsum = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        glm::ivec3 step(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        glm::ivec3 logical = base + step;
        if (glm::any(glm::greaterThanEqual(logical, v.counts))) continue;
        glm::ivec3 storage = v.storageOf(logical);
        int probe = v.probeBase + v.localIndex(storage);
        glm::ivec2 tile(storage.x + v.counts.x * storage.z, v.tileRow + storage.y);
        const ProbeRecord& rec = field.probes[std::size_t(probe)];
        if (rec.state == ProbeState::Off) continue;
        glm::vec3 probePos = v.basePosition(logical) + rec.offset;

        glm::vec3 toProbe = probePos - p;
        float toProbeLength = glm::length(toProbe);
        glm::vec3 dirToProbe = toProbeLength > 0.0f ? toProbe / toProbeLength : n;
        float wrap = 0.5f * (glm::dot(dirToProbe, n) + 1.0f);
        float w = wrap * wrap + 0.2f;

        glm::vec3 fromProbe = q - probePos;
        float r = glm::length(fromProbe);
        glm::vec3 dirFromProbe = r > 0.0f ? fromProbe / r : -n;
        glm::vec4 moments = field.distance.bilinearInTile(tile, oct::tileCoordinate(dirFromProbe, nd));
        w *= chebyshevVisibility(r, moments.x, moments.y);
        w = std::max(w, 1e-6f);
        // Crush tiny weights: the eye reads light leaking through a 1 % weight as full light.
        const float crush = 0.2f;
        if (w < crush) w *= w * w / (crush * crush);

        glm::vec3 tri = glm::mix(glm::vec3(1.0f) - alpha, alpha, glm::vec3(step));
        w *= tri.x * tri.y * tri.z;
        sum += w * lookup(tile, dirFromProbe);
        wsum += w;
    }
    if (weightSum) *weightSum = wsum;
    return wsum > 0.0f ? sum / wsum : glm::vec4(-1.0f);
}

// Cascades, finest first, each weighted by how far inside it p lies; the last takes the rest.
template <typename PerVolume>
glm::vec4 blendCascades(const ProbeField& field, glm::vec3 p, glm::vec4 none, PerVolume&& perVolume) {
    const auto& volumes = field.volumes();
    glm::vec4 sum(0.0f);
    float wsum = 0.0f;
    for (std::size_t v = 0; v < volumes.size() && wsum < 1.0f; ++v) {
        float w = v + 1 == volumes.size() ? 1.0f : volumeBlendWeight(volumes[v], p);
        w *= std::clamp(1.0f - wsum, 0.0f, 1.0f);
        if (w <= 0.0f) continue;
        sum += w * perVolume(int(v));
        wsum += w;
    }
    return wsum > 0.0f ? sum / wsum : none;
}

}  // namespace

glm::vec3 sampleVolumeIrradiance(const ProbeField& field, int vi, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer,
                                 float* weightSum) {
    const DdgiDesc& desc = field.desc();
    const int ni = desc.irradianceTexels;
    const glm::vec2 normalCoordinate = oct::tileCoordinate(n, ni);
    const float halfGamma = 0.5f * desc.irradianceGamma;
    float wsum = 0.0f;
    glm::vec4 mean = gatherCage(field, vi, p, n, toViewer, &wsum, [&](glm::ivec2 tile, glm::vec3) {
        glm::vec3 encoded = glm::max(glm::vec3(field.irradiance.bilinearInTile(tile, normalCoordinate)), glm::vec3(0.0f));
        // Interpolate in a sqrt-like space (gamma/2), as RTXGI does, then square.
        return glm::vec4(decodeHalf(encoded, halfGamma), 0.0f);
    });
    if (weightSum) *weightSum = wsum;
    if (!(wsum > 0.0f)) return glm::vec3(0.0f);
    glm::vec3 e(mean);
    return e * e;
}

glm::vec3 sampleIrradiance(const ProbeField& field, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer) {
    if (field.volumes().size() == 1) return sampleVolumeIrradiance(field, 0, p, n, toViewer);
    return glm::vec3(blendCascades(field, p, glm::vec4(0.0f), [&](int v) {
        return glm::vec4(sampleVolumeIrradiance(field, v, p, n, toViewer), 0.0f);
    }));
}

glm::vec4 sampleOcclusion(const ProbeField& field, glm::vec3 p, glm::vec3 n) {
    if (field.occlusion.texels.empty()) return glm::vec4(1.0f);
    const int nd = field.desc().distanceTexels;
    auto perVolume = [&](int v) {
        glm::vec4 value = gatherCage(field, v, p, n, n, nullptr, [&](glm::ivec2 tile, glm::vec3 dirFromProbe) {
            return field.occlusion.bilinearInTile(tile, oct::tileCoordinate(dirFromProbe, nd));
        });
        // No probe sees p: assume lit rather than invent a shadow.
        return value.x < 0.0f ? glm::vec4(1.0f) : value;
    };
    if (field.volumes().size() == 1) return perVolume(0);
    return blendCascades(field, p, glm::vec4(1.0f), perVolume);
}

}  // namespace voxgi
