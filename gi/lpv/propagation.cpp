#include "gi/lpv/propagation.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>

#include <tbb/parallel_for.h>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "gi/sh/sh.h"

namespace voxgi {

double polygonSolidAngle(glm::dvec3 eye, const std::vector<glm::dvec3>& corners) {
    // Van Oosterom & Strackee: tan(Omega / 2) = |a.(b x c)| / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|)
    double total = 0.0;
    for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
        glm::dvec3 a = corners[0] - eye, b = corners[i] - eye, c = corners[i + 1] - eye;
        double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
        double numerator = std::abs(glm::dot(a, glm::cross(b, c)));
        double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
        total += 2.0 * std::atan2(numerator, denominator);
    }
    return total;
}

namespace {

// A face of the unit cell centred at `center` with outward normal `normal`.
std::vector<glm::dvec3> faceCorners(glm::dvec3 center, glm::dvec3 normal) {
    glm::dvec3 u = std::abs(normal.x) > 0.5 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    glm::dvec3 v = glm::cross(normal, u);
    glm::dvec3 c = center + 0.5 * normal;
    return {c - 0.5 * u - 0.5 * v, c + 0.5 * u - 0.5 * v, c + 0.5 * u + 0.5 * v, c - 0.5 * u + 0.5 * v};
}

PropagationTables buildTables() {
    PropagationTables t{};
    t.axes = {glm::ivec3(1, 0, 0), glm::ivec3(-1, 0, 0), glm::ivec3(0, 1, 0),
              glm::ivec3(0, -1, 0), glm::ivec3(0, 0, 1), glm::ivec3(0, 0, -1)};
    for (int a = 0; a < 6; ++a) {
        glm::dvec3 axis(t.axes[std::size_t(a)]);
        glm::dvec3 dest = axis;  // destination centre; the source sits at the origin
        int f = 0;
        for (int n = 0; n < 6; ++n) {
            glm::dvec3 normal(t.axes[std::size_t(n)]);
            if (glm::dot(normal, axis) < -0.5) continue;  // the shared face
            PropagationFace& face = t.faces[std::size_t(a)][std::size_t(glm::dot(normal, axis) > 0.5 ? 0 : ++f)];
            glm::dvec3 faceCenter = dest + 0.5 * normal;
            face.direction = glm::vec3(glm::normalize(faceCenter));
            face.solidAngle = float(polygonSolidAngle(glm::dvec3(0.0), faceCorners(dest, normal)));
            face.normal = glm::vec3(normal);
        }
    }
    t.frontSolidAngle = t.faces[0][0].solidAngle;
    t.sideSolidAngle = t.faces[0][1].solidAngle;
    return t;
}

PropagationKernel buildKernel() {
    PropagationKernel k;
    auto& faces = k.faces;
    auto& unoccluded = k.unoccluded;
    const PropagationTables& t = propagationTables();
    auto toVec4 = [](const sh::Sh4& s) { return glm::vec4(s.c[0], s.c[1], s.c[2], s.c[3]); };
    for (std::size_t a = 0; a < 6; ++a) {
        glm::mat4 m(0.0f);
        for (std::size_t f = 0; f < 5; ++f) {
            const PropagationFace& pf = t.faces[a][f];
            FaceCoefficients& c = faces[a][f];
            c.sample = toVec4(sh::basis(pf.direction)) * pf.solidAngle;
            c.block = toVec4(sh::basis(-pf.direction));
            c.lobe = toVec4(sh::cosineLobe(pf.normal)) / sh::kPi;
            for (int col = 0; col < 4; ++col)
                for (int row = 0; row < 4; ++row) m[col][row] += c.lobe[row] * c.sample[col];
        }
        unoccluded[a] = m;
    }
    return k;
}

// The geometry volume at the centre of the face between `cell` and `cell + axis`: the mean of
// the face's 4 corner samples (one trilinear fetch on the GPU).
bool sharedFace(const BlockerVolume& gv, glm::ivec3 cell, const glm::ivec3& axis, glm::vec4& blocker,
                glm::vec3& albedo) {
    glm::ivec3 base = cell + glm::max(axis, glm::ivec3(0));
    int k = axis.x != 0 ? 0 : axis.y != 0 ? 1 : 2;
    int u = (k + 1) % 3, v = (k + 2) % 3;
    blocker = glm::vec4(0.0f);
    albedo = glm::vec3(0.0f);
    for (int du = 0; du < 2; ++du)
        for (int dv = 0; dv < 2; ++dv) {
            glm::ivec3 c = base;
            c[u] += du;
            c[v] += dv;
            std::size_t i = gv.cornerIndex(c);
            blocker += gv.blocker[i];
            albedo += gv.albedo[i];
        }
    blocker *= 0.25f;
    albedo *= 0.25f;
    return blocker != glm::vec4(0.0f);
}

float clamp01(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

// The reflected light's lobe: the blocker's SH with unit flux, its band-1 part limited to
// that of a clamped cosine (|c1| <= 2/sqrt(3) c0). Blockers fitted or merged from several
// surfaces can have a stronger band 1, and such a lobe, re-emitted step after step, would let
// the directional terms grow without bound while the flux stays put.
glm::vec4 reflectionShape(glm::vec4 blocker, float flux) {
    glm::vec4 shape = blocker / flux;
    glm::vec3 band1(shape.y, shape.z, shape.w);
    float limit = 1.1547005f * shape.x, length = glm::length(band1);
    if (length > limit) band1 *= limit / length;
    return glm::vec4(shape.x, band1);
}

}  // namespace

// The propagation operator of one cascade, built once per geometry volume: the 4x4 transfer
// matrix from each neighbour (occluded faces folded in) and from the cell itself (bounces).
// Steps then cost 6 + 1 matrix-vector products per colour and cell.
struct PropagationOperator {
    static constexpr std::int32_t kOpen = -1;  // use the unoccluded matrix of that axis
    std::vector<std::int32_t> gather;  // [cell * 6 + axis] -> index into gatherPool, or kOpen
    std::vector<glm::mat4> gatherPool;
    std::vector<std::int32_t> self;    // [cell] -> index of 3 consecutive matrices in selfPool, or -1
    std::vector<glm::mat4> selfPool;

    PropagationOperator(const BlockerVolume& gv, const CascadeGrid& grid, const PropagationOptions& opt) {
        const PropagationKernel& k = propagationKernel();
        const PropagationTables& t = propagationTables();
        gather.assign(grid.cellCount() * 6, kOpen);
        self.assign(grid.cellCount(), -1);
        if (!opt.occlusion || gv.blocker.empty()) return;
        // Slices are built in parallel into their own pools, then concatenated.
        const int n = grid.resolution;
        std::vector<std::vector<glm::mat4>> gatherSlices(static_cast<std::size_t>(n));
        std::vector<std::vector<glm::mat4>> selfSlices(static_cast<std::size_t>(n));
        tbb::parallel_for(0, n, [&](int z) {
            auto& gatherLocal = gatherSlices[std::size_t(z)];
            auto& selfLocal = selfSlices[std::size_t(z)];
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    glm::ivec3 d(x, y, z);
                    std::size_t di = grid.index(d);
                    for (std::size_t a = 0; a < 6; ++a) {
                        glm::vec4 blocker;
                        glm::vec3 albedo;
                        if (!sharedFace(gv, d - t.axes[a], t.axes[a], blocker, albedo)) continue;
                        glm::mat4 m(0.0f);
                        for (const FaceCoefficients& f : k.faces[a]) {
                            float pass = 1.0f - clamp01(glm::dot(blocker, f.block));
                            for (int col = 0; col < 4; ++col)
                                for (int row = 0; row < 4; ++row) m[col][row] += pass * f.lobe[row] * f.sample[col];
                        }
                        gather[di * 6 + a] = std::int32_t(gatherLocal.size());
                        gatherLocal.push_back(m);
                    }
                    if (!opt.bounces) continue;
                    // Light of this cell blocked at one of its own faces bounces back into it,
                    // shaped like the blocker's lobe normalized to unit flux.
                    glm::mat4 channel[3] = {glm::mat4(0.0f), glm::mat4(0.0f), glm::mat4(0.0f)};
                    bool any = false;
                    for (std::size_t a = 0; a < 6; ++a) {
                        glm::vec4 blocker;
                        glm::vec3 albedo;
                        if (!sharedFace(gv, d, t.axes[a], blocker, albedo)) continue;
                        float flux = blocker.x * (4.0f * sh::kPi * sh::kY00);
                        if (!(flux > 1e-12f) || albedo == glm::vec3(0.0f)) continue;
                        glm::vec4 shape = reflectionShape(blocker, flux);
                        glm::vec4 blocked(0.0f);  // dot with the cell's SH: the flux stopped at this face
                        for (const FaceCoefficients& f : k.faces[a]) blocked += clamp01(glm::dot(blocker, f.block)) * f.sample;
                        for (int c = 0; c < 3; ++c)
                            for (int col = 0; col < 4; ++col)
                                for (int row = 0; row < 4; ++row) channel[c][col][row] += albedo[c] * shape[row] * blocked[col];
                        any = true;
                    }
                    if (!any) continue;
                    self[di] = std::int32_t(selfLocal.size());
                    selfLocal.insert(selfLocal.end(), channel, channel + 3);
                }
        });
        // Rebase the slice-local indices onto the concatenated pools.
        for (int z = 0; z < n; ++z) {
            const auto gatherBase = std::int32_t(gatherPool.size()), selfBase = std::int32_t(selfPool.size());
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    std::size_t di = grid.index({x, y, z});
                    for (std::size_t a = 0; a < 6; ++a)
                        if (gather[di * 6 + a] != kOpen) gather[di * 6 + a] += gatherBase;
                    if (self[di] >= 0) self[di] += selfBase;
                }
            gatherPool.insert(gatherPool.end(), gatherSlices[std::size_t(z)].begin(), gatherSlices[std::size_t(z)].end());
            selfPool.insert(selfPool.end(), selfSlices[std::size_t(z)].begin(), selfSlices[std::size_t(z)].end());
        }
    }
};

namespace {

#if defined(__SSE2__)
// out += m * v with SSE: the columns are loaded once, the broadcast lanes of v multiply them.
inline void addTransfer(const glm::mat4& m, const glm::vec4& v, glm::vec4& out) {
    const float* c = &m[0][0];
    __m128 acc = _mm_loadu_ps(&out[0]);
    acc = _mm_add_ps(acc, _mm_mul_ps(_mm_loadu_ps(c), _mm_set1_ps(v.x)));
    acc = _mm_add_ps(acc, _mm_mul_ps(_mm_loadu_ps(c + 4), _mm_set1_ps(v.y)));
    acc = _mm_add_ps(acc, _mm_mul_ps(_mm_loadu_ps(c + 8), _mm_set1_ps(v.z)));
    acc = _mm_add_ps(acc, _mm_mul_ps(_mm_loadu_ps(c + 12), _mm_set1_ps(v.w)));
    _mm_storeu_ps(&out[0], acc);
}
#else
inline void addTransfer(const glm::mat4& m, const glm::vec4& v, glm::vec4& out) { out += m * v; }
#endif

void gatherCell(const LightVolume& in, const PropagationOperator& op, glm::ivec3 d, glm::vec4 out[3]) {
    const PropagationKernel& k = propagationKernel();
    const CascadeGrid& grid = in.grid;
    out[0] = out[1] = out[2] = glm::vec4(0.0f);
    const std::size_t di = grid.index(d);
    const std::size_t n = std::size_t(grid.resolution);
    // The six neighbours in the order of PropagationTables::axes (+x -x +y -y +z -z): the
    // source of light arriving along +x is the cell at -x, and so on.
    const bool has[6] = {d.x > 0, d.x + 1 < grid.resolution, d.y > 0, d.y + 1 < grid.resolution,
                         d.z > 0, d.z + 1 < grid.resolution};
    const std::size_t source[6] = {di - 1, di + 1, di - n, di + n, di - n * n, di + n * n};
    for (std::size_t a = 0; a < 6; ++a) {
        if (!has[a]) continue;
        const std::size_t si = source[a];
        const std::int32_t m = op.gather[di * 6 + a];
        const glm::mat4& transfer = m == PropagationOperator::kOpen ? k.unoccluded[a] : op.gatherPool[std::size_t(m)];
        addTransfer(transfer, in.r[si], out[0]);
        addTransfer(transfer, in.g[si], out[1]);
        addTransfer(transfer, in.b[si], out[2]);
    }
    if (op.self[di] < 0) return;
    const glm::mat4* channel = &op.selfPool[std::size_t(op.self[di])];
    addTransfer(channel[0], in.r[di], out[0]);
    addTransfer(channel[1], in.g[di], out[1]);
    addTransfer(channel[2], in.b[di], out[2]);
}

#if defined(__x86_64__)
// rg += m * (r | g) and b += m * b for a column-major 4x4 m, with FMA.
__attribute__((target("avx2,fma"), always_inline)) inline void addTransferAvx2(const float* c, const float* r,
                                                                               const float* g, const float* bIn,
                                                                               __m256& rg, __m128& b) {
    // Columns are broadcast into both lanes straight from memory; the blue components too.
    const __m256 v = _mm256_set_m128(_mm_loadu_ps(g), _mm_loadu_ps(r));
    const __m256 c0 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(c));
    const __m256 c1 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(c + 4));
    const __m256 c2 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(c + 8));
    const __m256 c3 = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(c + 12));
    rg = _mm256_fmadd_ps(c0, _mm256_permute_ps(v, 0x00), rg);
    rg = _mm256_fmadd_ps(c1, _mm256_permute_ps(v, 0x55), rg);
    rg = _mm256_fmadd_ps(c2, _mm256_permute_ps(v, 0xAA), rg);
    rg = _mm256_fmadd_ps(c3, _mm256_permute_ps(v, 0xFF), rg);
    b = _mm_fmadd_ps(_mm256_castps256_ps128(c0), _mm_broadcast_ss(bIn), b);
    b = _mm_fmadd_ps(_mm256_castps256_ps128(c1), _mm_broadcast_ss(bIn + 1), b);
    b = _mm_fmadd_ps(_mm256_castps256_ps128(c2), _mm_broadcast_ss(bIn + 2), b);
    b = _mm_fmadd_ps(_mm256_castps256_ps128(c3), _mm_broadcast_ss(bIn + 3), b);
}

// The same gather with AVX2 + FMA (chosen at run time when the CPU has them): red and green
// travel together in one 256-bit register, so each transfer matrix costs 4 + 4 FMAs.
__attribute__((target("avx2,fma"))) void gatherCellAvx2(const LightVolume& in, const PropagationOperator& op,
                                                         glm::ivec3 d, glm::vec4 out[3]) {
    const PropagationKernel& k = propagationKernel();
    const CascadeGrid& grid = in.grid;
    const std::size_t di = grid.index(d);
    const std::size_t n = std::size_t(grid.resolution);
    const bool has[6] = {d.x > 0, d.x + 1 < grid.resolution, d.y > 0, d.y + 1 < grid.resolution,
                         d.z > 0, d.z + 1 < grid.resolution};
    const std::size_t source[6] = {di - 1, di + 1, di - n, di + n, di - n * n, di + n * n};
    __m256 rg = _mm256_setzero_ps();
    __m128 b = _mm_setzero_ps();
    for (std::size_t a = 0; a < 6; ++a) {
        if (!has[a]) continue;
        const std::int32_t m = op.gather[di * 6 + a];
        const glm::mat4& t = m == PropagationOperator::kOpen ? k.unoccluded[a] : op.gatherPool[std::size_t(m)];
        addTransferAvx2(&t[0][0], &in.r[source[a]][0], &in.g[source[a]][0], &in.b[source[a]][0], rg, b);
    }
    _mm_storeu_ps(&out[0][0], _mm256_castps256_ps128(rg));
    _mm_storeu_ps(&out[1][0], _mm256_extractf128_ps(rg, 1));
    _mm_storeu_ps(&out[2][0], b);
    if (op.self[di] < 0) return;
    // Bounces: one matrix per colour.
    const glm::mat4* channel = &op.selfPool[std::size_t(op.self[di])];
    addTransfer(channel[0], in.r[di], out[0]);
    addTransfer(channel[1], in.g[di], out[1]);
    addTransfer(channel[2], in.b[di], out[2]);
}
#endif

using GatherFn = void (*)(const LightVolume&, const PropagationOperator&, glm::ivec3, glm::vec4*);

GatherFn chooseGather() {
#if defined(__x86_64__)
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return gatherCellAvx2;
#endif
    return gatherCell;
}

int brickSizeFor(int resolution) { return resolution % 8 == 0 ? 8 : 4; }

}  // namespace

CpuPropagator::CpuPropagator() = default;
CpuPropagator::~CpuPropagator() = default;
CpuPropagator::CpuPropagator(CpuPropagator&&) noexcept = default;
CpuPropagator& CpuPropagator::operator=(CpuPropagator&&) noexcept = default;

const PropagationTables& propagationTables() {
    static const PropagationTables tables = buildTables();
    return tables;
}

const PropagationKernel& propagationKernel() {
    static const PropagationKernel kernel = buildKernel();
    return kernel;
}

void CpuPropagator::step(const LightVolume& in, const BlockerVolume& geometry, const PropagationOptions& options,
                         LightVolume& out) {
    const CascadeGrid& grid = in.grid;
    if (out.r.size() != in.r.size()) out.reset(grid);
    out.grid = grid;
    const int n = grid.resolution;
    const PropagationOperator op(geometry, grid, options);
    tbb::parallel_for(0, n, [&](int z) {
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                glm::vec4 o[3];
                gatherCell(in, op, {x, y, z}, o);
                std::size_t i = grid.index({x, y, z});
                out.r[i] = o[0];
                out.g[i] = o[1];
                out.b[i] = o[2];
            }
    });
}

void CpuPropagator::propagate(const LightVolume& injected, const BlockerVolume& geometry, int steps,
                              const PropagationOptions& options, LightVolume& accumulated, bool sparse) {
    const CascadeGrid& grid = injected.grid;
    accumulated = injected;
    if (ping_.grid.resolution != grid.resolution || ping_.r.size() != grid.cellCount()) {
        ping_.reset(grid);
        pong_.reset(grid);
    }
    ping_ = injected;
    pong_.grid = grid;
    pong_.clear();
    const int bs = brickSizeFor(grid.resolution);
    const int nb = grid.resolution / bs;
    const std::size_t brickCount = std::size_t(nb) * std::size_t(nb) * std::size_t(nb);
    auto brickIndex = [nb](glm::ivec3 b) {
        return (std::size_t(b.z) * std::size_t(nb) + std::size_t(b.y)) * std::size_t(nb) + std::size_t(b.x);
    };
    // Which bricks of the input hold light.
    std::vector<std::uint8_t> lit(brickCount, 0), pongLit(brickCount, 0);
    for (int z = 0; z < grid.resolution; ++z)
        for (int y = 0; y < grid.resolution; ++y)
            for (int x = 0; x < grid.resolution; ++x)
                if (!injected.isZero(grid.index({x, y, z}))) lit[brickIndex(glm::ivec3(x, y, z) / bs)] = 1;
    // Bounces make a cell's own light feed back, so a lit brick stays active.
    stats_.totalBricks = brickCount;
    auto t0 = std::chrono::steady_clock::now();
    const bool sameGeometry = operator_ && operatorOptions_.occlusion == options.occlusion &&
                              operatorOptions_.bounces == options.bounces &&
                              operatorGeometry_.grid.resolution == geometry.grid.resolution &&
                              operatorGeometry_.blocker == geometry.blocker && operatorGeometry_.albedo == geometry.albedo;
    if (!sameGeometry) {
        operator_ = std::make_unique<PropagationOperator>(geometry, grid, options);
        operatorGeometry_ = geometry;
        operatorOptions_ = options;
    }
    const PropagationOperator& op = *operator_;
    static const GatherFn gather = chooseGather();
    auto t1 = std::chrono::steady_clock::now();
    stats_.operatorMs = std::chrono::duration<double, std::milli>(t1 - t0).count();
    std::vector<glm::ivec3> active;
    std::vector<std::uint8_t> litOut(brickCount);
    for (int iteration = 0; iteration < steps; ++iteration) {
        active.clear();
        for (int z = 0; z < nb; ++z)
            for (int y = 0; y < nb; ++y)
                for (int x = 0; x < nb; ++x) {
                    glm::ivec3 b(x, y, z);
                    bool on = !sparse || lit[brickIndex(b)];
                    for (int a = 0; a < 6 && !on; ++a) {
                        glm::ivec3 nbr = b + propagationTables().axes[std::size_t(a)];
                        on = glm::all(glm::greaterThanEqual(nbr, glm::ivec3(0))) &&
                             glm::all(glm::lessThan(nbr, glm::ivec3(nb))) && lit[brickIndex(nbr)];
                    }
                    if (on) active.push_back(b);
                    else if (pongLit[brickIndex(b)]) {
                        // Stale light from two steps ago: clear it.
                        for (int k = 0; k < bs; ++k)
                            for (int j = 0; j < bs; ++j)
                                for (int i = 0; i < bs; ++i) {
                                    std::size_t c = grid.index(b * bs + glm::ivec3(i, j, k));
                                    pong_.r[c] = pong_.g[c] = pong_.b[c] = glm::vec4(0.0f);
                                }
                    }
                }
        std::fill(litOut.begin(), litOut.end(), 0);
        tbb::parallel_for(std::size_t(0), active.size(), [&](std::size_t ai) {
            glm::ivec3 b = active[ai];
            bool any = false;
            for (int k = 0; k < bs; ++k)
                for (int j = 0; j < bs; ++j)
                    for (int i = 0; i < bs; ++i) {
                        glm::ivec3 d = b * bs + glm::ivec3(i, j, k);
                        glm::vec4 o[3];
                        gather(ping_, op, d, o);
                        std::size_t c = grid.index(d);
                        pong_.r[c] = o[0];
                        pong_.g[c] = o[1];
                        pong_.b[c] = o[2];
                        accumulated.r[c] += o[0];
                        accumulated.g[c] += o[1];
                        accumulated.b[c] += o[2];
                        any = any || o[0] != glm::vec4(0.0f) || o[1] != glm::vec4(0.0f) || o[2] != glm::vec4(0.0f);
                    }
            litOut[brickIndex(b)] = any ? 1 : 0;
        });
        stats_.activeBricks = active.size();
        std::swap(ping_, pong_);
        pongLit = lit;
        lit = litOut;
    }
    stats_.stepsMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
}

}  // namespace voxgi
