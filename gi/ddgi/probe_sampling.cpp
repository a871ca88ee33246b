#include "gi/ddgi/probe_sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

constexpr int kCage = 8;

// x^(gamma/2) with a fast path for the default gamma 5 (x^2.5 = x^2 sqrt x); same values as pow.
float decodeHalf(float x, float halfGamma) {
    if (halfGamma == 2.5f) return x * x * std::sqrt(x);
    if (halfGamma == 1.0f) return x;
    return std::pow(x, halfGamma);
}


// A bilinear footprint inside a tile (Atlas::bilinearInTile's arithmetic): the texel offset of
// its lower-left texel within the tile and the two fractions. `local` >= 0.5 always (tile
// coordinates start at 1), so truncation is the floor.
struct Footprint {
    std::uint32_t offset;
    float tx, ty;
};
Footprint footprint(float lx, float ly, int tile) {
    float px = lx - 0.5f, py = ly - 0.5f;
    int fx = int(px), fy = int(py);
    Footprint f;
    f.tx = px - float(fx);
    f.ty = py - float(fy);
    fx = std::clamp(fx, 0, tile - 2);
    fy = std::clamp(fy, 0, tile - 2);
    f.offset = std::uint32_t(fy * tile + fx);
    return f;
}

glm::vec4 bilinearAt(const glm::vec4* q, int tile, float tx, float ty) {
    const glm::vec4 &a = q[0], &b = q[1], &c = q[tile], &d = q[tile + 1];
    return glm::mix(glm::mix(a, b, tx), glm::mix(c, d, tx), ty);
}

}  // namespace

bool samplingPathSupported(SamplingPath path) {
#if defined(__x86_64__)
    if (path == SamplingPath::Avx2) return __builtin_cpu_supports("avx2");
#endif
    return path == SamplingPath::Scalar;
}

SamplingPath bestSamplingPath() {
    static const SamplingPath best =
        samplingPathSupported(SamplingPath::Avx2) ? SamplingPath::Avx2 : SamplingPath::Scalar;
    return best;
}

ProbeSampler::ProbeSampler(const ProbeField& field, SamplingPath path) : field_(field), path_(path) {
    if (!samplingPathSupported(path)) throw std::logic_error("probe sampling: path not supported by this CPU");
    const int tileD = oct::tileSize(field.desc().distanceTexels), tileI = oct::tileSize(field.desc().irradianceTexels);
    for (const ProbeVolume& pv : field.volumes()) {
        Volume v;
        v.counts = pv.counts;
        v.origin = pv.origin;
        v.spacing = pv.spacing;
        v.biasScale = pv.minSpacing();
        v.first = int(probes_.size());
        for (int c = 0; c < kCage; ++c) {
            glm::ivec3 step(c & 1, (c >> 1) & 1, (c >> 2) & 1);
            glm::bvec3 inside = glm::lessThan(step, pv.counts);
            glm::ivec3 s = glm::ivec3(inside) * step;
            v.cornerOffset[c] = s.x + pv.counts.x * (s.y + pv.counts.y * s.z);
            v.cornerInside[c] = glm::all(inside) ? 1.0f : 0.0f;
        }
        volumes_.push_back(v);
        for (int z = 0; z < pv.counts.z; ++z)
            for (int y = 0; y < pv.counts.y; ++y)
                for (int x = 0; x < pv.counts.x; ++x) {
                    glm::ivec3 logical(x, y, z);
                    glm::ivec3 storage = pv.storageOf(logical);
                    int probe = pv.probeBase + pv.localIndex(storage);
                    const ProbeRecord& rec = field.probes[std::size_t(probe)];
                    glm::ivec2 tile(storage.x + pv.counts.x * storage.z, pv.tileRow + storage.y);
                    std::uint32_t tileIndex = std::uint32_t(tile.y * field.distance.tilesX + tile.x);
                    CageProbe c;
                    c.position = pv.basePosition(logical) + rec.offset;
                    c.live = rec.state == ProbeState::Off ? 0.0f : 1.0f;
                    c.distanceTexel = tileIndex * std::uint32_t(tileD * tileD);
                    c.irradianceTexel = std::uint32_t(tile.y * field.irradiance.tilesX + tile.x) * std::uint32_t(tileI * tileI);
                    probes_.push_back(c);
                }
    }
}

// The cage in three passes over eight lanes: per-probe data in, the weights (arithmetic only,
// which the compiler vectorizes), then the texel fetches and the weighted sum. Off probes and
// corners outside the volume get weight 0, which is the reference's `continue`.
template <bool kOcclusion>
glm::vec4 ProbeSampler::gather(const Volume& v, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer, float* weightSum) const {
    const DdgiDesc& desc = field_.desc();
    glm::vec3 q = p + (n * desc.normalBias + toViewer * desc.viewBias) * v.biasScale;
    glm::vec3 rel = (q - v.origin) / v.spacing;
    glm::ivec3 base = glm::clamp(glm::ivec3(glm::floor(rel)), glm::ivec3(0), glm::max(v.counts - 2, glm::ivec3(0)));
    glm::vec3 alpha = glm::clamp(rel - glm::vec3(base), 0.0f, 1.0f);
    for (int a = 0; a < 3; ++a)
        if (v.counts[a] < 2) alpha[a] = 0.0f;

    alignas(32) float px[kCage], py[kCage], pz[kCage], live[kCage], tri[kCage];
    const CageProbe* cage[kCage];
    for (int c = 0; c < kCage; ++c) {
        glm::ivec3 step(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        glm::ivec3 l = base + step;
        bool inside = l.x < v.counts.x && l.y < v.counts.y && l.z < v.counts.z;
        const CageProbe& probe = probes_[std::size_t(inside ? v.first + l.x + v.counts.x * (l.y + v.counts.y * l.z) : v.first)];
        cage[c] = &probe;
        px[c] = probe.position.x, py[c] = probe.position.y, pz[c] = probe.position.z;
        live[c] = inside ? probe.live : 0.0f;
        float tx = step.x ? alpha.x : 1.0f - alpha.x, ty = step.y ? alpha.y : 1.0f - alpha.y;
        float tz = step.z ? alpha.z : 1.0f - alpha.z;
        tri[c] = tx * ty * tz;
    }

    const int nd = desc.distanceTexels;
    // Divisions are the slow part: one reciprocal per length instead of one per component
    // (results move by an ulp; the GLSL twin divides per component, parity holds at 1e-6).
    // The octahedral encoding of the unit direction is that of the unnormalized one.
    const float nn = n.x * n.x + n.y * n.y + n.z * n.z;
    alignas(32) float wrapWeight[kCage], r[kCage], lx[kCage], ly[kCage];
    for (int c = 0; c < kCage; ++c) {
        float ax = px[c] - p.x, ay = py[c] - p.y, az = pz[c] - p.z;
        float toLength = std::sqrt(ax * ax + ay * ay + az * az);
        float cosine = toLength > 0.0f ? (ax * n.x + ay * n.y + az * n.z) / toLength : nn;
        float wrap = 0.5f * (cosine + 1.0f);
        wrapWeight[c] = wrap * wrap + 0.2f;

        float bx = q.x - px[c], by = q.y - py[c], bz = q.z - pz[c];
        float len = std::sqrt(bx * bx + by * by + bz * bz);
        r[c] = len;
        // The direction probe -> point (-n when the point sits on the probe).
        float dx = len > 0.0f ? bx : -n.x, dy = len > 0.0f ? by : -n.y, dz = len > 0.0f ? bz : -n.z;
        // oct::tileCoordinate inline (encode, fold the lower hemisphere, to tile coordinates).
        float l1 = std::abs(dx) + std::abs(dy) + std::abs(dz);
        float inv = l1 > 0.0f ? 1.0f / l1 : 0.0f;
        float ex = dx * inv, ey = dy * inv;
        float fx = (1.0f - std::abs(ey)) * (ex >= 0.0f ? 1.0f : -1.0f);
        float fy = (1.0f - std::abs(ex)) * (ey >= 0.0f ? 1.0f : -1.0f);
        bool fold = dz < 0.0f && l1 > 0.0f;
        ex = fold ? fx : ex;
        ey = fold ? fy : ey;
        lx[c] = 1.0f + std::clamp(ex * 0.5f + 0.5f, 0.0f, 1.0f) * float(nd);
        ly[c] = 1.0f + std::clamp(ey * 0.5f + 0.5f, 0.0f, 1.0f) * float(nd);
    }

    const int tileD = nd + 2;
    alignas(32) float mean[kCage], meanSquare[kCage];
    alignas(32) float value[4][kCage];
    const glm::vec4* distance = field_.distance.texels.data();
    for (int c = 0; c < kCage; ++c) {
        Footprint f = footprint(lx[c], ly[c], tileD);
        std::size_t at = std::size_t(cage[c]->distanceTexel + f.offset);
        glm::vec4 m = bilinearAt(distance + at, tileD, f.tx, f.ty);
        mean[c] = m.x, meanSquare[c] = m.y;
        if constexpr (kOcclusion) {
            glm::vec4 o = bilinearAt(field_.occlusion.texels.data() + at, tileD, f.tx, f.ty);
            for (int k = 0; k < 4; ++k) value[k][c] = o[k];
        }
    }
    if constexpr (!kOcclusion) {
        const int ni = desc.irradianceTexels, tileI = ni + 2;
        glm::vec2 nc = oct::tileCoordinate(n, ni);
        Footprint f = footprint(nc.x, nc.y, tileI);
        const glm::vec4* irradiance = field_.irradiance.texels.data();
        const float halfGamma = 0.5f * desc.irradianceGamma;
        for (int c = 0; c < kCage; ++c) {
            glm::vec4 e = bilinearAt(irradiance + cage[c]->irradianceTexel + f.offset, tileI, f.tx, f.ty);
            // Interpolate in a sqrt-like space (gamma/2), as RTXGI does; squared at the end.
            for (int k = 0; k < 3; ++k) value[k][c] = decodeHalf(std::max(e[k], 0.0f), halfGamma);
            value[3][c] = 0.0f;
        }
    }

    alignas(32) float weight[kCage];
    for (int c = 0; c < kCage; ++c) {
        float w = wrapWeight[c] * chebyshevVisibility(r[c], mean[c], meanSquare[c]);
        w = std::max(w, 1e-6f);
        // Crush tiny weights: the eye reads light leaking through a 1 % weight as full light.
        const float crush = 0.2f;
        if (w < crush) w *= w * w / (crush * crush);
        weight[c] = w * tri[c] * live[c];
    }
    glm::vec4 sum(0.0f);
    float wsum = 0.0f;
    for (int c = 0; c < kCage; ++c) {
        sum += weight[c] * glm::vec4(value[0][c], value[1][c], value[2][c], value[3][c]);
        wsum += weight[c];
    }
    if (weightSum) *weightSum = wsum;
    return wsum > 0.0f ? sum / wsum : glm::vec4(-1.0f);
}

glm::vec3 ProbeSampler::volumeIrradiance(int vi, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer, float* weightSum) const {
    float wsum = 0.0f;
    const Volume& v = volumes_[std::size_t(vi)];
#if defined(__x86_64__)
    glm::vec4 mean = path_ == SamplingPath::Avx2 ? gatherAvx2<false>(v, p, n, toViewer, &wsum)
                                                 : gather<false>(v, p, n, toViewer, &wsum);
#else
    glm::vec4 mean = gather<false>(v, p, n, toViewer, &wsum);
#endif
    if (weightSum) *weightSum = wsum;
    if (!(wsum > 0.0f)) return glm::vec3(0.0f);
    glm::vec3 e(mean);
    return e * e;
}

namespace {
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

glm::vec3 ProbeSampler::irradiance(glm::vec3 p, glm::vec3 n, glm::vec3 toViewer) const {
    if (volumes_.size() == 1) return volumeIrradiance(0, p, n, toViewer, nullptr);
    return glm::vec3(blendCascades(field_, p, glm::vec4(0.0f), [&](int v) {
        return glm::vec4(volumeIrradiance(v, p, n, toViewer, nullptr), 0.0f);
    }));
}

glm::vec4 ProbeSampler::occlusion(glm::vec3 p, glm::vec3 n) const {
    if (field_.occlusion.texels.empty()) return glm::vec4(1.0f);
    auto perVolume = [&](int v) {
        const Volume& volume = volumes_[std::size_t(v)];
#if defined(__x86_64__)
        glm::vec4 value = path_ == SamplingPath::Avx2 ? gatherAvx2<true>(volume, p, n, n, nullptr)
                                                      : gather<true>(volume, p, n, n, nullptr);
#else
        glm::vec4 value = gather<true>(volume, p, n, n, nullptr);
#endif
        // No probe sees p: assume lit rather than invent a shadow.
        return value.x < 0.0f ? glm::vec4(1.0f) : value;
    };
    if (volumes_.size() == 1) return perVolume(0);
    return blendCascades(field_, p, glm::vec4(1.0f), perVolume);
}

glm::vec3 sampleIrradiance(const ProbeField& field, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer) {
    return ProbeSampler(field).irradiance(p, n, toViewer);
}

glm::vec3 sampleVolumeIrradiance(const ProbeField& field, int volume, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer,
                                 float* weightSum) {
    return ProbeSampler(field).volumeIrradiance(volume, p, n, toViewer, weightSum);
}

glm::vec4 sampleOcclusion(const ProbeField& field, glm::vec3 p, glm::vec3 n) {
    return ProbeSampler(field).occlusion(p, n);
}

}  // namespace voxgi
