// One propagation step over a brick, 8 cells per SIMD register (GCC vector extensions: the
// same source compiles for AVX-512VL, AVX2 + FMA and SSE, chosen at run time by the CPU).
#include <cmath>
#include <algorithm>
#include <cstring>
#include <stdexcept>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include "gi/lpv/detail/propagation_soa.h"

// Every function taking or returning a vector is internal and always inlined, so the warning
// about the AVX calling convention of 32-byte vectors concerns no real call.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace voxgi::lpv_detail {

namespace {

using v8 = float __attribute__((vector_size(32)));
using m8 = int __attribute__((vector_size(32)));
#define VOXGI_INLINE inline __attribute__((always_inline))

VOXGI_INLINE v8 load8(const float* p) {
    v8 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
VOXGI_INLINE void store8(float* p, const v8& v) { std::memcpy(p, &v, sizeof v); }

// The coefficients of each axis: the 5 faces are symmetric about the axis, so the open
// transfer couples only (Y00, axis) among themselves and keeps the two other band-1 terms on
// the diagonal; face f samples (Y00, axis, its normal's) and re-emits into (Y00, its normal's).
struct AxisConstants {
    float m00, m0a, ma0, maa, m11, m22;
    float s0[5], sa[5], sn[5], l0[5], ln[5];
};

struct Constants {
    AxisConstants axis[6];
};

// Also checks the sparsity the step relies on against the derived kernel.
Constants buildConstants() {
    const PropagationKernel& kernel = propagationKernel();
    Constants out{};
    auto expectZero = [](float v, float scale) {
        if (std::abs(v) > 1e-6f * scale)
            throw std::logic_error("LPV propagation: a transfer coefficient lies outside the assumed sparsity");
    };
    for (int a = 0; a < 6; ++a) {
        const int k = a / 2, ca = shOf(k), c1 = shOf(otherDim(k, 0)), c2 = shOf(otherDim(k, 1));
        const glm::mat4& m = kernel.unoccluded[std::size_t(a)];
        AxisConstants& c = out.axis[a];
        c = {m[0][0], m[ca][0], m[0][ca], m[ca][ca], m[c1][c1], m[c2][c2], {}, {}, {}, {}, {}};
        for (int col = 0; col < 4; ++col)
            for (int row = 0; row < 4; ++row)
                if (!(((row == 0 || row == ca) && (col == 0 || col == ca)) || row == col)) expectZero(m[col][row], c.m00);
        for (int f = 0; f < 5; ++f) {
            const FaceCoefficients& fc = kernel.faces[std::size_t(a)][std::size_t(f)];
            const int cn = f == 0 ? ca : f <= 2 ? c1 : c2;
            c.s0[f] = fc.sample[0];
            c.sa[f] = fc.sample[ca];
            c.sn[f] = f == 0 ? 0.0f : fc.sample[cn];
            c.l0[f] = fc.lobe[0];
            c.ln[f] = fc.lobe[cn];
            for (int i = 1; i < 4; ++i) {
                if (i != ca && i != cn) expectZero(fc.sample[i], fc.sample[0]);
                if (i != cn) expectZero(fc.lobe[i], fc.lobe[0]);
            }
        }
    }
    return out;
}

const Constants& constants() {
    static const Constants c = buildConstants();
    return c;
}

// o += the light arriving along axis A from the source cells at `src` (colour channel 0;
// channel i at src + i * stride); `pass` is null for an open face, else the 5 faces' pass
// factors (see PropagationOperator::pass).
template <int A>
VOXGI_INLINE void gatherAxis(const AxisConstants& K, const float* src, std::size_t stride, const float* pass,
                             v8 o[4]) {
    constexpr int k = A / 2, ca = shOf(k), c1 = shOf(otherDim(k, 0)), c2 = shOf(otherDim(k, 1));
    const v8 i0 = load8(src), ia = load8(src + ca * stride);
    const v8 i1 = load8(src + c1 * stride), i2 = load8(src + c2 * stride);
    if (!pass) {
        o[0] += K.m00 * i0 + K.m0a * ia;
        o[ca] += K.ma0 * i0 + K.maa * ia;
        o[c1] += K.m11 * i1;
        o[c2] += K.m22 * i2;
        return;
    }
    v8 t = (K.s0[0] * i0 + K.sa[0] * ia) * load8(pass);
    o[0] += K.l0[0] * t;
    o[ca] += K.ln[0] * t;
    t = (K.s0[1] * i0 + K.sa[1] * ia + K.sn[1] * i1) * load8(pass + kLanes);
    o[0] += K.l0[1] * t;
    o[c1] += K.ln[1] * t;
    t = (K.s0[2] * i0 + K.sa[2] * ia + K.sn[2] * i1) * load8(pass + 2 * kLanes);
    o[0] += K.l0[2] * t;
    o[c1] += K.ln[2] * t;
    t = (K.s0[3] * i0 + K.sa[3] * ia + K.sn[3] * i2) * load8(pass + 3 * kLanes);
    o[0] += K.l0[3] * t;
    o[c2] += K.ln[3] * t;
    t = (K.s0[4] * i0 + K.sa[4] * ia + K.sn[4] * i2) * load8(pass + 4 * kLanes);
    o[0] += K.l0[4] * t;
    o[c2] += K.ln[4] * t;
}

VOXGI_INLINE float brickKernel(const PropagationOperator& op, const SoaLight& in, SoaLight& out, SoaLight& acc,
                              glm::ivec3 brick) {
    const SoaLayout& L = op.layout;
    const std::size_t cs = L.channelSize;
    const auto sx = std::ptrdiff_t(L.sx), sxy = std::ptrdiff_t(L.sx * L.sy);
    const AxisConstants* K = constants().axis;
    // Lanes past the grid's end (resolutions that are not whole runs) must stay dark.
    v8 keep;
    for (int l = 0; l < kLanes; ++l) keep[l] = brick.x * kLanes + l < L.n ? 1.0f : 0.0f;
    const bool partial = (brick.x + 1) * kLanes > L.n;
    v8 total{};
    const int y1 = std::min(L.n, (brick.y + 1) * kLanes), z1 = std::min(L.n, (brick.z + 1) * kLanes);
    for (int z = brick.z * kLanes; z < z1; ++z)
        for (int y = brick.y * kLanes; y < y1; ++y) {
            const std::size_t i = L.index(brick.x * kLanes, y, z);
            const std::size_t run = L.run(brick.x, y, z);
            const float* const* pass = &op.pass[run * 6];
            const float* bounce = op.bounce[run];
            for (int c = 0; c < 3; ++c) {
                const float* base = in.channel(4 * c) + i;
                v8 o[4] = {};
                // The source of light arriving along +x is the cell at -x, and so on.
                gatherAxis<0>(K[0], base - 1, cs, pass[0], o);
                gatherAxis<1>(K[1], base + 1, cs, pass[1], o);
                gatherAxis<2>(K[2], base - sx, cs, pass[2], o);
                gatherAxis<3>(K[3], base + sx, cs, pass[3], o);
                gatherAxis<4>(K[4], base - sxy, cs, pass[4], o);
                gatherAxis<5>(K[5], base + sxy, cs, pass[5], o);
                if (bounce) {
                    const float* m = bounce + c * 16 * kLanes;
                    const v8 own[4] = {load8(base), load8(base + cs), load8(base + 2 * cs), load8(base + 3 * cs)};
                    for (int col = 0; col < 4; ++col)
                        for (int row = 0; row < 4; ++row) o[row] += load8(m + (col * 4 + row) * kLanes) * own[col];
                }
                for (int k = 0; k < 4; ++k) {
                    if (partial) o[k] *= keep;
                    const std::size_t channelOffset = std::size_t(4 * c + k) * cs + i;
                    store8(out.data.data() + channelOffset, o[k]);
                    float* a = acc.data.data() + channelOffset;
                    store8(a, load8(a) + o[k]);
                    total += v8(m8(o[k]) & 0x7fffffff);  // |o[k]|
                }
            }
        }
    float sum = 0.0f;
    for (int l = 0; l < kLanes; ++l) sum += total[l];
    return sum;
}

#if defined(__x86_64__)
// AVX-512VL keeps 256-bit vectors but gives 32 registers and broadcast operands.
__attribute__((target("avx512f,avx512vl,avx2,fma"))) float brickAvx512(const PropagationOperator& op, const SoaLight& in,
                                                                     SoaLight& out, SoaLight& acc, glm::ivec3 brick) {
    return brickKernel(op, in, out, acc, brick);
}

__attribute__((target("avx2,fma"))) float brickAvx2(const PropagationOperator& op, const SoaLight& in, SoaLight& out,
                                                   SoaLight& acc, glm::ivec3 brick) {
    return brickKernel(op, in, out, acc, brick);
}
#endif

float brickBaseline(const PropagationOperator& op, const SoaLight& in, SoaLight& out, SoaLight& acc, glm::ivec3 brick) {
    return brickKernel(op, in, out, acc, brick);
}

using BrickFn = float (*)(const PropagationOperator&, const SoaLight&, SoaLight&, SoaLight&, glm::ivec3);

BrickFn brickFn(SimdLevel level) {
    switch (level) {
#if defined(__x86_64__)
        case SimdLevel::Avx512: return brickAvx512;
        case SimdLevel::Avx2: return brickAvx2;
#endif
        default: return brickBaseline;
    }
}

// Light that has decayed below FLT_MIN (1.2e-38) is treated as zero while a brick runs: on
// x86, arithmetic on subnormal floats takes ~100 times as long, and a long propagation whose
// light has died away (lpv.steps in the thousands) spent almost all its time there (4000
// steps: 1.8 s, 8000: 34 s). The caller's floating-point mode is restored afterwards.
class SubnormalsFlushed {
public:
#if defined(__SSE__)
    SubnormalsFlushed() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero); }
    ~SubnormalsFlushed() { _mm_setcsr(saved_); }

private:
    static constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;
    unsigned saved_;
#endif
};

}  // namespace

bool simdLevelSupported(SimdLevel level) {
#if defined(__x86_64__)
    if (level == SimdLevel::Avx512) return __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512f");
    if (level == SimdLevel::Avx2) return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#endif
    return level == SimdLevel::Baseline;
}

SimdLevel bestSimdLevel() {
    for (SimdLevel level : {SimdLevel::Avx512, SimdLevel::Avx2})
        if (simdLevelSupported(level)) return level;
    return SimdLevel::Baseline;
}

float propagateBrick(const PropagationOperator& op, const SoaLight& in, SoaLight& out, SoaLight& acc,
                    glm::ivec3 brick) {
    static const BrickFn fn = brickFn(bestSimdLevel());
    const SubnormalsFlushed flushed;
    return fn(op, in, out, acc, brick);
}

float propagateBrick(const PropagationOperator& op, const SoaLight& in, SoaLight& out, SoaLight& acc,
                    glm::ivec3 brick, SimdLevel level) {
    if (!simdLevelSupported(level)) throw std::logic_error("LPV propagation: SIMD level not supported by this CPU");
    const SubnormalsFlushed flushed;
    return brickFn(level)(op, in, out, acc, brick);
}

}  // namespace voxgi::lpv_detail
