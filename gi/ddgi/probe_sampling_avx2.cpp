// ProbeSampler's cage on eight AVX2 lanes, one lane per cage probe. Compiled for AVX2 by
// function attribute only (the rest of the build targets baseline x86-64); probe_sampling.cpp
// calls it where bestSamplingPath() found the instructions.
// The weights are bit for bit those of the scalar gather: the same operations in the same
// order, and no FMA (the compiler would contract mul + add, and Chebyshev's variance, a
// difference of two near-equal moments, turns an ulp into a visible 1e-3). Only the order of
// the final weighted sum differs.
#if defined(__x86_64__)

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "gi/ddgi/probe_sampling.h"
#include "gi/octahedral/octahedral.h"

// The helpers taking or returning vectors are always inlined into AVX2 code, so the warning
// about the calling convention of 32-byte vectors concerns no real call.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace voxgi {

namespace {

#define VOXGI_AVX2 __attribute__((target("avx2")))
#define VOXGI_AVX2_INLINE inline __attribute__((target("avx2"), always_inline))

VOXGI_AVX2_INLINE __m256 unpackLo64(__m256 a, __m256 b) {
    return _mm256_castpd_ps(_mm256_unpacklo_pd(_mm256_castps_pd(a), _mm256_castps_pd(b)));
}
VOXGI_AVX2_INLINE __m256 unpackHi64(__m256 a, __m256 b) {
    return _mm256_castpd_ps(_mm256_unpackhi_pd(_mm256_castps_pd(a), _mm256_castps_pd(b)));
}

// Rows k and k + 4 of eight 4-float rows, side by side: after the in-lane transpose the eight
// lanes of each column come out in cage order.
struct Columns {
    __m256 x, y, z, w;
};
VOXGI_AVX2_INLINE Columns transpose(const __m128 (&row)[8]) {
    __m256 r0 = _mm256_insertf128_ps(_mm256_castps128_ps256(row[0]), row[4], 1);
    __m256 r1 = _mm256_insertf128_ps(_mm256_castps128_ps256(row[1]), row[5], 1);
    __m256 r2 = _mm256_insertf128_ps(_mm256_castps128_ps256(row[2]), row[6], 1);
    __m256 r3 = _mm256_insertf128_ps(_mm256_castps128_ps256(row[3]), row[7], 1);
    __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);
    __m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);
    return {unpackLo64(t0, t2), unpackHi64(t0, t2), unpackLo64(t1, t3), unpackHi64(t1, t3)};
}

// .x, .y of two neighbouring float4 texels: (a.x, a.y, b.x, b.y).
VOXGI_AVX2_INLINE __m128 loadPairXY(const glm::vec4* t) {
    __m128d lo = _mm_load_sd(reinterpret_cast<const double*>(t));
    return _mm_castpd_ps(_mm_loadh_pd(lo, reinterpret_cast<const double*>(t + 1)));
}

// glm::mix(x, y, a) = x (1 - a) + y a.
VOXGI_AVX2_INLINE __m256 mix(__m256 x, __m256 y, __m256 a) {
    return _mm256_add_ps(_mm256_mul_ps(x, _mm256_sub_ps(_mm256_set1_ps(1.0f), a)), _mm256_mul_ps(y, a));
}
VOXGI_AVX2_INLINE __m256 select(__m256 mask, __m256 ifTrue, __m256 ifFalse) {
    return _mm256_blendv_ps(ifFalse, ifTrue, mask);
}
VOXGI_AVX2_INLINE __m256 absolute(__m256 x) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), x); }

template <int kMask>
VOXGI_AVX2_INLINE __m256 cornerFractions(float t) {
    return _mm256_blend_ps(_mm256_set1_ps(1.0f - t), _mm256_set1_ps(t), kMask);
}
// e (x, y of the folded octahedral square) to a tile coordinate, 1 + clamp(e/2 + 1/2) texels.
VOXGI_AVX2_INLINE __m256 toTile(__m256 e, __m256 texels) {
    const __m256 half = _mm256_set1_ps(0.5f), one = _mm256_set1_ps(1.0f);
    __m256 unit = _mm256_min_ps(_mm256_max_ps(_mm256_add_ps(_mm256_mul_ps(e, half), half), _mm256_setzero_ps()), one);
    return _mm256_add_ps(one, _mm256_mul_ps(unit, texels));
}
// a.x b.x + a.y b.y + a.z b.z, left to right.
VOXGI_AVX2_INLINE __m256 dot3(__m256 ax, __m256 ay, __m256 az, __m256 bx, __m256 by, __m256 bz) {
    return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(ax, bx), _mm256_mul_ps(ay, by)), _mm256_mul_ps(az, bz));
}

// The float4 bilinear lookups of two lanes, (lane c | lane c + 1), as glm::mix nests them:
// each texel row is a (left, right) pair of float4, weighted (1 - tx | tx), summed across.
struct Rows {
    __m256 lower, upper;  // (row of lane c | row of lane c + 1)
};
VOXGI_AVX2_INLINE __m256 sumHalves(__m256 c0, __m256 c1) {
    return _mm256_add_ps(_mm256_permute2f128_ps(c0, c1, 0x20), _mm256_permute2f128_ps(c0, c1, 0x31));
}
VOXGI_AVX2_INLINE __m256 rowWeights(float tx) { return _mm256_setr_ps(1 - tx, 1 - tx, 1 - tx, 1 - tx, tx, tx, tx, tx); }
VOXGI_AVX2_INLINE Rows bilinearRows(const glm::vec4* q0, const glm::vec4* q1, int tile, __m256 w0, __m256 w1) {
    return {sumHalves(_mm256_mul_ps(_mm256_loadu_ps(&q0[0].x), w0), _mm256_mul_ps(_mm256_loadu_ps(&q1[0].x), w1)),
            sumHalves(_mm256_mul_ps(_mm256_loadu_ps(&q0[tile].x), w0), _mm256_mul_ps(_mm256_loadu_ps(&q1[tile].x), w1))};
}
// mix(lower, upper, ty) with ty per half.
VOXGI_AVX2_INLINE __m256 mixRows(const Rows& r, __m256 ty) { return mix(r.lower, r.upper, ty); }
VOXGI_AVX2_INLINE __m256 broadcastPair(__m256 v, int c) {
    return _mm256_permutevar8x32_ps(v, _mm256_setr_epi32(c, c, c, c, c + 1, c + 1, c + 1, c + 1));
}

}  // namespace

template <bool kOcclusion>
VOXGI_AVX2 glm::vec4 ProbeSampler::gatherAvx2(const Volume& v, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer,
                                              float* weightSum) const {
    constexpr int kCage = 8;
    const DdgiDesc& desc = field_.desc();
    // The cage base and the trilinear fractions, per axis as in gather.
    float q[3], alpha[3];
    int base[3];
    for (int a = 0; a < 3; ++a) {
        q[a] = p[a] + (n[a] * desc.normalBias + toViewer[a] * desc.viewBias) * v.biasScale;
        float rel = (q[a] - v.origin[a]) / v.spacing[a];
        int b = int(std::floor(rel));
        int top = v.counts[a] - 2 > 0 ? v.counts[a] - 2 : 0;
        base[a] = b < 0 ? 0 : b > top ? top : b;
        float t = rel - float(base[a]);
        t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
        alpha[a] = v.counts[a] < 2 ? 0.0f : t;
    }
    const CageProbe* cageBase = probes_.data() + v.first + base[0] + v.counts.x * (base[1] + v.counts.y * base[2]);
    const CageProbe* cage[kCage];
    __m128 record[kCage];
    for (int c = 0; c < kCage; ++c) {
        cage[c] = cageBase + v.cornerOffset[c];
        static_assert(offsetof(CageProbe, live) == 3 * sizeof(float), "position, live load as one float4");
        record[c] = _mm_loadu_ps(&cage[c]->position.x);
    }
    // The irradiance footprint depends on n only: start its fetches before the long chain of
    // arithmetic that decides the distance footprints (atlases of big volumes miss the caches).
    const int ni = desc.irradianceTexels, tileI = ni + 2;
    const glm::vec2 nc = oct::tileCoordinate(n, ni);
    const float nfx = nc.x - 0.5f, nfy = nc.y - 0.5f;
    const int ifx = std::min(int(nfx), tileI - 2), ify = std::min(int(nfy), tileI - 2);
    const glm::vec4* irradiance = field_.irradiance.texels.data() + std::size_t(ify * tileI + ifx);
    if constexpr (!kOcclusion)
        for (int c = 0; c < kCage; ++c) {
            _mm_prefetch(reinterpret_cast<const char*>(irradiance + cage[c]->irradianceTexel), _MM_HINT_T0);
            _mm_prefetch(reinterpret_cast<const char*>(irradiance + cage[c]->irradianceTexel + tileI), _MM_HINT_T0);
        }
    const Columns probe = transpose(record);
    const __m256 live = _mm256_mul_ps(probe.w, _mm256_loadu_ps(v.cornerInside));

    // Lane c takes alpha on the axes where its cage step is 1, 1 - alpha elsewhere.
    const __m256 tri = _mm256_mul_ps(_mm256_mul_ps(cornerFractions<0xaa>(alpha[0]), cornerFractions<0xcc>(alpha[1])),
                                     cornerFractions<0xf0>(alpha[2]));

    const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
    const __m256 nx = _mm256_set1_ps(n.x), ny = _mm256_set1_ps(n.y), nz = _mm256_set1_ps(n.z);
    // Wrap: cosine between n and the direction to the probe (|n|^2 when p sits on the probe).
    __m256 wrapWeight;
    {
        __m256 ax = _mm256_sub_ps(probe.x, _mm256_set1_ps(p.x)), ay = _mm256_sub_ps(probe.y, _mm256_set1_ps(p.y)),
               az = _mm256_sub_ps(probe.z, _mm256_set1_ps(p.z));
        __m256 length = _mm256_sqrt_ps(dot3(ax, ay, az, ax, ay, az));
        __m256 dot = dot3(ax, ay, az, nx, ny, nz);
        __m256 cosine = select(_mm256_cmp_ps(length, zero, _CMP_GT_OQ), _mm256_div_ps(dot, length),
                               _mm256_set1_ps(n.x * n.x + n.y * n.y + n.z * n.z));
        __m256 wrap = _mm256_mul_ps(_mm256_set1_ps(0.5f), _mm256_add_ps(cosine, one));
        wrapWeight = _mm256_add_ps(_mm256_mul_ps(wrap, wrap), _mm256_set1_ps(0.2f));
    }
    // Distance probe -> biased point, and where its direction falls in the distance tile.
    const int nd = desc.distanceTexels, tileD = nd + 2;
    __m256 r, lx, ly;
    {
        __m256 bx = _mm256_sub_ps(_mm256_set1_ps(q[0]), probe.x), by = _mm256_sub_ps(_mm256_set1_ps(q[1]), probe.y),
               bz = _mm256_sub_ps(_mm256_set1_ps(q[2]), probe.z);
        r = _mm256_sqrt_ps(dot3(bx, by, bz, bx, by, bz));
        // -n when the point sits on the probe.
        __m256 away = _mm256_cmp_ps(r, zero, _CMP_GT_OQ);
        __m256 dx = select(away, bx, _mm256_sub_ps(zero, nx)), dy = select(away, by, _mm256_sub_ps(zero, ny)),
               dz = select(away, bz, _mm256_sub_ps(zero, nz));
        __m256 l1 = _mm256_add_ps(_mm256_add_ps(absolute(dx), absolute(dy)), absolute(dz));
        __m256 nonzero = _mm256_cmp_ps(l1, zero, _CMP_GT_OQ);
        __m256 inv = _mm256_and_ps(nonzero, _mm256_div_ps(one, l1));
        __m256 ex = _mm256_mul_ps(dx, inv), ey = _mm256_mul_ps(dy, inv);
        // Lower hemisphere folded over the corners: (1 - |ey|, 1 - |ex|) with the signs of
        // (ex, ey), where a sign is + unless the value is < 0 (or NaN, as in the scalar code).
        const __m256 sign = _mm256_set1_ps(-0.0f);
        __m256 fx = _mm256_xor_ps(_mm256_sub_ps(one, absolute(ey)), _mm256_and_ps(_mm256_cmp_ps(ex, zero, _CMP_NGE_UQ), sign));
        __m256 fy = _mm256_xor_ps(_mm256_sub_ps(one, absolute(ex)), _mm256_and_ps(_mm256_cmp_ps(ey, zero, _CMP_NGE_UQ), sign));
        __m256 fold = _mm256_and_ps(_mm256_cmp_ps(dz, zero, _CMP_LT_OQ), nonzero);
        ex = select(fold, fx, ex);
        ey = select(fold, fy, ey);
        lx = toTile(ex, _mm256_set1_ps(float(nd)));
        ly = toTile(ey, _mm256_set1_ps(float(nd)));
    }
    // Footprints: the texel below-left of each lookup (coordinates >= 0.5, so truncation is
    // the floor) and the fractions, taken before the footprint is clamped into the tile.
    __m256 tx, ty;
    alignas(32) std::int32_t offset[kCage];
    {
        const __m256 half = _mm256_set1_ps(0.5f);
        __m256 px = _mm256_sub_ps(lx, half), py = _mm256_sub_ps(ly, half);
        __m256i fx = _mm256_cvttps_epi32(px), fy = _mm256_cvttps_epi32(py);
        tx = _mm256_sub_ps(px, _mm256_cvtepi32_ps(fx));
        ty = _mm256_sub_ps(py, _mm256_cvtepi32_ps(fy));
        const __m256i lo = _mm256_setzero_si256(), hi = _mm256_set1_epi32(tileD - 2);
        fx = _mm256_min_epi32(_mm256_max_epi32(fx, lo), hi);
        fy = _mm256_min_epi32(_mm256_max_epi32(fy, lo), hi);
        __m256i at = _mm256_add_epi32(_mm256_mullo_epi32(fy, _mm256_set1_epi32(tileD)), fx);
        _mm256_store_si256(reinterpret_cast<__m256i*>(offset), at);
    }
    // Distance moments: only .x, .y of each texel, four lanes per 128-bit half.
    const glm::vec4* distance = field_.distance.texels.data();
    __m256 mean, meanSquare;
    {
        __m128 lower[kCage], upper[kCage];
        for (int c = 0; c < kCage; ++c) {
            const glm::vec4* t = distance + std::size_t(cage[c]->distanceTexel) + std::size_t(offset[c]);
            lower[c] = loadPairXY(t);
            upper[c] = loadPairXY(t + tileD);
        }
        Columns l = transpose(lower), u = transpose(upper);
        mean = mix(mix(l.x, l.z, tx), mix(u.x, u.z, tx), ty);
        meanSquare = mix(mix(l.y, l.w, tx), mix(u.y, u.w, tx), ty);
    }

    // Chebyshev visibility, cubed: 1 at or before the mean, 0 beyond it without variance.
    __m256 weight;
    {
        __m256 variance = _mm256_max_ps(_mm256_sub_ps(meanSquare, _mm256_mul_ps(mean, mean)), zero);
        __m256 d = _mm256_sub_ps(r, mean);
        __m256 bound = _mm256_div_ps(variance, _mm256_add_ps(variance, _mm256_mul_ps(d, d)));
        bound = _mm256_and_ps(_mm256_cmp_ps(variance, zero, _CMP_GT_OQ), _mm256_mul_ps(_mm256_mul_ps(bound, bound), bound));
        __m256 visibility = select(_mm256_cmp_ps(r, mean, _CMP_LE_OQ), one, bound);
        __m256 w = _mm256_max_ps(_mm256_mul_ps(wrapWeight, visibility), _mm256_set1_ps(1e-6f));
        // Crush weights under 0.2 (w^3 / 0.2^2): see gather.
        const __m256 crush = _mm256_set1_ps(0.2f);
        __m256 crushed = _mm256_mul_ps(w, _mm256_div_ps(_mm256_mul_ps(w, w), _mm256_mul_ps(crush, crush)));
        w = select(_mm256_cmp_ps(w, crush, _CMP_LT_OQ), crushed, w);
        weight = _mm256_mul_ps(_mm256_mul_ps(w, tri), live);
    }

    // The weighted float4 sum, two lanes per register (lane c | lane c + 1).
    __m256 sum = zero;
    if constexpr (kOcclusion) {
        alignas(32) float fracX[kCage], fracY[kCage];
        _mm256_store_ps(fracX, tx);
        _mm256_store_ps(fracY, ty);
        const glm::vec4* occlusion = field_.occlusion.texels.data();
        for (int c = 0; c < kCage; c += 2) {
            const glm::vec4* t0 = occlusion + std::size_t(cage[c]->distanceTexel) + std::size_t(offset[c]);
            const glm::vec4* t1 = occlusion + std::size_t(cage[c + 1]->distanceTexel) + std::size_t(offset[c + 1]);
            Rows rows = bilinearRows(t0, t1, tileD, rowWeights(fracX[c]), rowWeights(fracX[c + 1]));
            __m256 pairY = _mm256_setr_ps(fracY[c], fracY[c], fracY[c], fracY[c], fracY[c + 1], fracY[c + 1],
                                          fracY[c + 1], fracY[c + 1]);
            sum = _mm256_add_ps(sum, _mm256_mul_ps(broadcastPair(weight, c), mixRows(rows, pairY)));
        }
    } else {
        // One footprint for all lanes: the normal's direction in each probe's irradiance tile.
        const __m256 wx = rowWeights(nfx - float(int(nfx))), wy = _mm256_set1_ps(nfy - float(int(nfy)));
        const float halfGamma = 0.5f * desc.irradianceGamma;
        for (int c = 0; c < kCage; c += 2) {
            __m256 e = mixRows(bilinearRows(irradiance + cage[c]->irradianceTexel, irradiance + cage[c + 1]->irradianceTexel,
                                            tileI, wx, wx),
                               wy);
            // Decoded to the gamma/2 space (x^2.5 = x^2 sqrt x for the default gamma 5).
            e = _mm256_max_ps(e, zero);
            if (halfGamma == 2.5f) {
                e = _mm256_mul_ps(_mm256_mul_ps(e, e), _mm256_sqrt_ps(e));
            } else if (halfGamma != 1.0f) {
                alignas(32) float x[8];
                _mm256_store_ps(x, e);
                for (float& value : x) value = std::pow(value, halfGamma);
                e = _mm256_load_ps(x);
            }
            sum = _mm256_add_ps(sum, _mm256_mul_ps(broadcastPair(weight, c), e));
        }
    }
    alignas(16) float total[4];
    _mm_store_ps(total, _mm_add_ps(_mm256_castps256_ps128(sum), _mm256_extractf128_ps(sum, 1)));
    __m128 w4 = _mm_add_ps(_mm256_castps256_ps128(weight), _mm256_extractf128_ps(weight, 1));
    w4 = _mm_add_ps(w4, _mm_movehl_ps(w4, w4));
    const float wsum = _mm_cvtss_f32(_mm_add_ss(w4, _mm_movehdup_ps(w4)));
    if (weightSum) *weightSum = wsum;
    if (!(wsum > 0.0f)) return glm::vec4(-1.0f);
    // The irradiance .w is not a channel (the scalar path sums zeros there).
    return glm::vec4(total[0] / wsum, total[1] / wsum, total[2] / wsum, kOcclusion ? total[3] / wsum : 0.0f);
}

template glm::vec4 ProbeSampler::gatherAvx2<false>(const Volume&, glm::vec3, glm::vec3, glm::vec3, float*) const;
template glm::vec4 ProbeSampler::gatherAvx2<true>(const Volume&, glm::vec3, glm::vec3, glm::vec3, float*) const;

}  // namespace voxgi

#endif
