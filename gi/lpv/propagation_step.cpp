// One propagation step over a brick, 8 cells per SIMD register (GCC vector extensions: the
// same source compiles for AVX-512VL, AVX2 + FMA and SSE, chosen at run time by the CPU).
#include <cmath>
#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "gi/lpv/detail/propagation_soa.h"
#include "gi/lpv/detail/subnormals_flushed.h"

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

// One colour's 4 SH coefficients of a run's output, as named registers: an array indexed by the
// axes' template constants kept them on the stack (zeroed by rep stos, stored in halves), which
// cost a third of the kernel's time.
struct Coefficients {
    v8 c0{}, c1{}, c2{}, c3{};
    template <int I>
    VOXGI_INLINE v8& c() {
        if constexpr (I == 0) return c0;
        else if constexpr (I == 1) return c1;
        else if constexpr (I == 2) return c2;
        else return c3;
    }
};

// Every lane moved one to the right, lane 0 taken from lane 7 of `before` (the cells at x - 1
// of a run), and one to the left, lane 7 taken from lane 0 of `after` (the cells at x + 1).
VOXGI_INLINE v8 shiftedRight(v8 before, v8 run) {
#if defined(__clang__)
    return __builtin_shufflevector(before, run, 7, 8, 9, 10, 11, 12, 13, 14);
#else
    return __builtin_shuffle(before, run, m8{7, 8, 9, 10, 11, 12, 13, 14});
#endif
}
VOXGI_INLINE v8 shiftedLeft(v8 run, v8 after) {
#if defined(__clang__)
    return __builtin_shufflevector(run, after, 1, 2, 3, 4, 5, 6, 7, 8);
#else
    return __builtin_shuffle(run, after, m8{1, 2, 3, 4, 5, 6, 7, 8});
#endif
}

// The 8 cells a run gathers from along one axis, coefficient Ch of one colour (`at` points at
// the colour's first coefficient in the run's block; SoaLayout): the run beside it along y or z,
// or its own cells moved by one along x, the end lane from the run before or after.
struct RunSource {
    const float* at;
    template <int Ch>
    VOXGI_INLINE v8 get() const { return load8(at + Ch * kLanes); }
};
struct CellsBefore {
    const float* at;
    template <int Ch>
    VOXGI_INLINE v8 get() const { return shiftedRight(load8(at - kRunFloats + Ch * kLanes), load8(at + Ch * kLanes)); }
};
struct CellsAfter {
    const float* at;
    template <int Ch>
    VOXGI_INLINE v8 get() const { return shiftedLeft(load8(at + Ch * kLanes), load8(at + kRunFloats + Ch * kLanes)); }
};

// o += the light arriving along axis A from the source cells `src`; `pass` is null for an open
// face, else the 5 faces' pass factors (see PropagationOperator::pass).
template <int A, class Source>
VOXGI_INLINE void gatherAxis(const AxisConstants& K, const Source& src, const float* pass, Coefficients& o) {
    constexpr int k = A / 2, ca = shOf(k), c1 = shOf(otherDim(k, 0)), c2 = shOf(otherDim(k, 1));
    const v8 i0 = src.template get<0>(), ia = src.template get<ca>();
    const v8 i1 = src.template get<c1>(), i2 = src.template get<c2>();
    if (!pass) {
        o.c<0>() += K.m00 * i0 + K.m0a * ia;
        o.c<ca>() += K.ma0 * i0 + K.maa * ia;
        o.c<c1>() += K.m11 * i1;
        o.c<c2>() += K.m22 * i2;
        return;
    }
    v8 t = (K.s0[0] * i0 + K.sa[0] * ia) * load8(pass);
    o.c<0>() += K.l0[0] * t;
    o.c<ca>() += K.ln[0] * t;
    t = (K.s0[1] * i0 + K.sa[1] * ia + K.sn[1] * i1) * load8(pass + kLanes);
    o.c<0>() += K.l0[1] * t;
    o.c<c1>() += K.ln[1] * t;
    t = (K.s0[2] * i0 + K.sa[2] * ia + K.sn[2] * i1) * load8(pass + 2 * kLanes);
    o.c<0>() += K.l0[2] * t;
    o.c<c1>() += K.ln[2] * t;
    t = (K.s0[3] * i0 + K.sa[3] * ia + K.sn[3] * i2) * load8(pass + 3 * kLanes);
    o.c<0>() += K.l0[3] * t;
    o.c<c2>() += K.ln[3] * t;
    t = (K.s0[4] * i0 + K.sa[4] * ia + K.sn[4] * i2) * load8(pass + 4 * kLanes);
    o.c<0>() += K.l0[4] * t;
    o.c<c2>() += K.ln[4] * t;
}

// One run of 8 cells, whose blocks (SoaLayout::block) start at in and out: out = transfer(in);
// with acc, acc = (acc + carried) + out (carried: null, or the previous step's output of the same
// run, added here as that step left the sum alone); returns |out| per lane. sy, sz: floats to the
// next run along y, z.
VOXGI_INLINE v8 runKernel(const PropagationOperator& op, const float* in, float* out, float* acc,
                         const float* carried, std::size_t run, std::ptrdiff_t sy, std::ptrdiff_t sz, const v8* keep) {
    const AxisConstants* K = constants().axis;
    const float* const* pass = &op.pass[run * 6];
    const float* bounce = op.bounce[run];
    v8 total{};
    for (int c = 0; c < 3; ++c) {
        const std::size_t colour = std::size_t(4 * c * kLanes);
        const float* base = in + colour;
        Coefficients o;
        // The source of light arriving along +x is the cell at -x, and so on.
        gatherAxis<0>(K[0], CellsBefore{base}, pass[0], o);
        gatherAxis<1>(K[1], CellsAfter{base}, pass[1], o);
        gatherAxis<2>(K[2], RunSource{base - sy}, pass[2], o);
        gatherAxis<3>(K[3], RunSource{base + sy}, pass[3], o);
        gatherAxis<4>(K[4], RunSource{base - sz}, pass[4], o);
        gatherAxis<5>(K[5], RunSource{base + sz}, pass[5], o);
        if (bounce) {
            const float* m = bounce + c * 16 * kLanes;
            for (int col = 0; col < 4; ++col) {
                const v8 own = load8(base + col * kLanes);
                o.c0 += load8(m + (col * 4 + 0) * kLanes) * own;
                o.c1 += load8(m + (col * 4 + 1) * kLanes) * own;
                o.c2 += load8(m + (col * 4 + 2) * kLanes) * own;
                o.c3 += load8(m + (col * 4 + 3) * kLanes) * own;
            }
        }
        if (keep) {
            o.c0 *= *keep;
            o.c1 *= *keep;
            o.c2 *= *keep;
            o.c3 *= *keep;
        }
        const v8* coefficients[4] = {&o.c0, &o.c1, &o.c2, &o.c3};
        for (int k = 0; k < 4; ++k) {
            const v8 v = *coefficients[k];
            const std::size_t at = colour + std::size_t(k * kLanes);
            store8(out + at, v);
            if (acc) {
                v8 sum = load8(acc + at);
                if (carried) sum += load8(carried + at);
                store8(acc + at, sum + v);
            }
            total += v8(m8(v) & 0x7fffffff);  // |o_k|
        }
    }
    return total;
}

// Rows [y0, y1) of plane z: the runs of the step's active bricks, row after row (a row of the
// light is contiguous, SoaLayout, so each row of the input, output and sum streams through once).
VOXGI_INLINE void rowsKernel(const PropagationOperator& op, const StepBuffers& b, const StepBricks& bricks, int z,
                             int y0, int y1) {
    const SoaLayout& L = op.layout;
    const auto sy = std::ptrdiff_t(L.rowStride), sz = std::ptrdiff_t(L.rowStride * L.sy);
    // Lanes past the grid's end (resolutions that are not whole runs) must stay dark.
    const int lastRun = L.runsX - 1;
    v8 keep;
    for (int l = 0; l < kLanes; ++l) keep[l] = lastRun * kLanes + l < L.n ? 1.0f : 0.0f;
    const bool partial = L.runsX * kLanes > L.n;
    const float* in = b.in->data.data();
    float* out = b.out->data.data();
    float* acc = b.acc ? b.acc->data.data() : nullptr;
    const float* carried = b.carried ? b.carried->data.data() : nullptr;
    for (int y = y0; y < y1; ++y) {
        const std::size_t brickRow = (std::size_t(z / kLanes) * std::size_t(bricks.count.y) + std::size_t(y / kLanes)) *
                                     std::size_t(bricks.count.x);
        for (int rx = 0; rx < L.runsX; ++rx) {
            const std::size_t brick = brickRow + std::size_t(rx);
            if (!bricks.active[brick]) continue;
            const std::size_t i = L.block(rx, y, z);
            float* total = bricks.laneTotals + brick * kLanes;
            const float* carry = carried && b.carriedActive[brick] ? carried + i : nullptr;
            store8(total, load8(total) + runKernel(op, in + i, out + i, acc ? acc + i : nullptr, carry, L.run(rx, y, z),
                                                   sy, sz, partial && rx == lastRun ? &keep : nullptr));
        }
    }
}

#if defined(__x86_64__)
// AVX-512VL keeps 256-bit vectors but gives 32 registers and broadcast operands.
__attribute__((target("avx512f,avx512vl,avx2,fma"))) void rowsAvx512(const PropagationOperator& op, const StepBuffers& b,
                                                                    const StepBricks& bricks, int z, int y0, int y1) {
    rowsKernel(op, b, bricks, z, y0, y1);
}

__attribute__((target("avx2,fma"))) void rowsAvx2(const PropagationOperator& op, const StepBuffers& b,
                                                  const StepBricks& bricks, int z, int y0, int y1) {
    rowsKernel(op, b, bricks, z, y0, y1);
}
#endif

void rowsBaseline(const PropagationOperator& op, const StepBuffers& b, const StepBricks& bricks, int z, int y0, int y1) {
    rowsKernel(op, b, bricks, z, y0, y1);
}

using RowsFn = void (*)(const PropagationOperator&, const StepBuffers&, const StepBricks&, int, int, int);

RowsFn rowsFn(SimdLevel level) {
    switch (level) {
#if defined(__x86_64__)
        case SimdLevel::Avx512: return rowsAvx512;
        case SimdLevel::Avx2: return rowsAvx2;
#endif
        default: return rowsBaseline;
    }
}


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

void propagateRows(const PropagationOperator& op, const StepBuffers& buffers, const StepBricks& bricks, int z, int y0,
                   int y1) {
    static const RowsFn fn = rowsFn(bestSimdLevel());
    const detail::SubnormalsFlushed flushed;
    fn(op, buffers, bricks, z, y0, y1);
}

void propagateRows(const PropagationOperator& op, const StepBuffers& buffers, const StepBricks& bricks, int z, int y0,
                   int y1, SimdLevel level) {
    if (!simdLevelSupported(level)) throw std::logic_error("LPV propagation: SIMD level not supported by this CPU");
    const detail::SubnormalsFlushed flushed;
    rowsFn(level)(op, buffers, bricks, z, y0, y1);
}

}  // namespace voxgi::lpv_detail
