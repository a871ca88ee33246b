#include "gi/lpv/propagation.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>

#include <tbb/parallel_for.h>

#include "gi/lpv/detail/propagation_soa.h"
#include "gi/sh/sh.h"
#include "shaders/shared/constants.h"

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
            c.lobe = toVec4(sh::cosineLobe(pf.normal)) / shading::kPi;
            for (int col = 0; col < 4; ++col)
                for (int row = 0; row < 4; ++row) m[col][row] += c.lobe[row] * c.sample[col];
        }
        unoccluded[a] = m;
    }
    return k;
}

}  // namespace

const PropagationTables& propagationTables() {
    static const PropagationTables tables = buildTables();
    return tables;
}

const PropagationKernel& propagationKernel() {
    static const PropagationKernel kernel = buildKernel();
    return kernel;
}

struct CpuPropagator::Work {
    lpv_detail::SoaLight ping, pong, acc;
    std::unique_ptr<lpv_detail::PropagationOperator> op;
    BlockerVolume operatorGeometry;
    PropagationOptions operatorOptions;
};

CpuPropagator::CpuPropagator() = default;
CpuPropagator::~CpuPropagator() = default;
CpuPropagator::CpuPropagator(CpuPropagator&&) noexcept = default;
CpuPropagator& CpuPropagator::operator=(CpuPropagator&&) noexcept = default;

namespace {

// Bricks of 8 x 8 runs x 8 runs' rows (8^3 cells where the resolution allows).
struct BrickGrid {
    glm::ivec3 count;
    explicit BrickGrid(const lpv_detail::SoaLayout& l)
        : count(l.runsX, (l.n + lpv_detail::kLanes - 1) / lpv_detail::kLanes,
                (l.n + lpv_detail::kLanes - 1) / lpv_detail::kLanes) {}
    std::size_t size() const { return std::size_t(count.x) * std::size_t(count.y) * std::size_t(count.z); }
    std::size_t index(glm::ivec3 b) const {
        return (std::size_t(b.z) * std::size_t(count.y) + std::size_t(b.y)) * std::size_t(count.x) + std::size_t(b.x);
    }
    glm::ivec3 brick(std::size_t i) const {
        const auto cx = std::size_t(count.x), cy = std::size_t(count.y);
        return {int(i % cx), int(i / cx % cy), int(i / (cx * cy))};
    }
    bool contains(glm::ivec3 b) const { return glm::all(glm::greaterThanEqual(b, glm::ivec3(0))) && glm::all(glm::lessThan(b, count)); }
};

// Zeroes every channel of a brick's cells (light left from two steps ago).
void clearBrick(lpv_detail::SoaLight& light, glm::ivec3 b) {
    using lpv_detail::kLanes;
    const auto& l = light.layout;
    for (int z = b.z * kLanes; z < std::min(l.n, (b.z + 1) * kLanes); ++z)
        for (int y = b.y * kLanes; y < std::min(l.n, (b.y + 1) * kLanes); ++y)
            std::fill_n(light.data.begin() + std::ptrdiff_t(l.block(b.x, y, z)), lpv_detail::kRunFloats, 0.0f);
}

// One step over every active brick, one task per column of bricks (8 x 8 rows).
void runStep(const lpv_detail::PropagationOperator& op, const lpv_detail::StepBuffers& buffers,
             const lpv_detail::StepBricks& bricks) {
    using lpv_detail::kLanes;
    const int n = op.layout.n;
    tbb::parallel_for(0, bricks.count.y * bricks.count.z, [&](int column) {
        const int by = column % bricks.count.y, bz = column / bricks.count.y;
        const std::uint8_t* row = bricks.active + std::size_t(column) * std::size_t(bricks.count.x);
        if (std::none_of(row, row + bricks.count.x, [](std::uint8_t on) { return on != 0; })) return;
        for (int z = bz * kLanes; z < std::min(n, (bz + 1) * kLanes); ++z)
            propagateRows(op, buffers, bricks, z, by * kLanes, std::min(n, (by + 1) * kLanes));
    });
}

// Two steps in one pass through memory: planes along z in order, the second step two planes
// behind the first, so the first step's output is read back from cache and the sum is read and
// written once for both. The first step writes `first.out`; the second reads it and writes
// `second.out`, which may be the first step's input: by the time the second step writes plane
// z, the first has read plane z for the last time (at plane z + 1). One task per row of bricks
// and plane; each wave waits for the last (the second step at z needs the first at z + 1 whole).
void runStepPair(const lpv_detail::PropagationOperator& op, const lpv_detail::StepBuffers& first,
                 const lpv_detail::StepBricks& firstBricks, const lpv_detail::StepBuffers& second,
                 const lpv_detail::StepBricks& secondBricks) {
    using lpv_detail::kLanes;
    const int n = op.layout.n, rows = firstBricks.count.y;
    for (int wave = 0; wave < n + 2; ++wave) {
        tbb::parallel_for(0, 2 * rows, [&](int task) {
            const bool isFirst = task < rows;
            const int z = isFirst ? wave : wave - 2, by = task % rows;
            if (z < 0 || z >= n) return;
            propagateRows(op, isFirst ? first : second, isFirst ? firstBricks : secondBricks, z, by * kLanes,
                          std::min(n, (by + 1) * kLanes));
        });
    }
}

// A paired pass keeps about 8 planes in flight (the input's around the first step, the first
// step's output around the second). Pairs paid on the 2-core EPYC VM at 32^3 and 64^3 (0.6 and
// 2 MiB in flight) and lost a little at 128^3 (7.2 MiB; docs/lpv.md), so up to 4 MiB, a core's
// share of a last-level cache (the size the OS reports is often the host's: 64 MiB here).
bool pairedPassFitsCache(const lpv_detail::SoaLayout& layout) {
    constexpr double kPairedPassBytes = 4.0 * 1024.0 * 1024.0;
    const double plane = double(layout.rowStride) * double(layout.sy) * double(sizeof(float));
    return 8.0 * plane <= kPairedPassBytes;
}

}  // namespace

bool propagationConverged(const std::vector<double>& stepLight, double lightSoFar) {
    if (stepLight.empty()) return false;
    const double last = stepLight.back();
    if (last == 0.0) return true;  // nothing left to move: every later step adds zero
    // LPV light spreads like a diffusion: once it has crossed the volume, what is still in
    // transit decays geometrically at the rate of the volume's slowest mode (half-lives of
    // about 75 steps at 32^3 and 280 at 64^3 in the Cornell box), for thousands of steps.
    // The rate q is measured over the last kConvergenceWindow steps; the light the remaining
    // steps could still add is at most last * q / (1 - q).
    if (stepLight.size() <= std::size_t(kConvergenceWindow)) return false;
    const double earlier = stepLight[stepLight.size() - 1 - std::size_t(kConvergenceWindow)];
    if (!(earlier > last)) return false;
    const double q = std::pow(last / earlier, 1.0 / kConvergenceWindow);
    return last * q / (1.0 - q) < kConvergenceTolerance * lightSoFar;
}

void CpuPropagator::step(const LightVolume& in, const BlockerVolume& geometry, const PropagationOptions& options,
                         LightVolume& out) {
    using namespace lpv_detail;
    const CascadeGrid& grid = in.grid;
    const SoaLayout layout(grid.resolution);
    SoaLight from, to, acc;
    from.reset(layout);
    to.reset(layout);
    acc.reset(layout);
    from.fromVolume(in);
    const PropagationOperator op(geometry, grid, options);
    const BrickGrid bricks(layout);
    const std::vector<std::uint8_t> active(bricks.size(), 1);
    std::vector<float> laneTotals(bricks.size() * kLanes, 0.0f);
    runStep(op, {&from, &to, &acc, nullptr, nullptr}, {bricks.count, active.data(), laneTotals.data()});
    if (out.r.size() != grid.cellCount()) out.reset(grid);
    out.grid = grid;
    to.toVolume(out);
}

void CpuPropagator::propagate(const LightVolume& injected, const BlockerVolume& geometry, int steps,
                              const PropagationOptions& options, LightVolume& accumulated, bool sparse) {
    using namespace lpv_detail;
    const CascadeGrid& grid = injected.grid;
    if (!work_) work_ = std::make_unique<Work>();
    Work& w = *work_;
    const SoaLayout layout(grid.resolution);
    if (!(w.ping.layout == layout) || w.ping.data.empty()) {
        w.ping.reset(layout);
        w.pong.reset(layout);
        w.acc.reset(layout);
    } else {
        std::fill(w.pong.data.begin(), w.pong.data.end(), 0.0f);
    }
    w.ping.fromVolume(injected);
    w.acc.data = w.ping.data;  // accumulated starts as the injected light

    const BrickGrid bricks(layout);
    // Which bricks of the input hold light, and how much light there is (the start of the
    // light sent so far, for the convergence test below).
    std::vector<std::uint8_t> lit(bricks.size(), 0), pongLit(bricks.size(), 0);
    double lightSoFar = 0.0;
    for (int z = 0; z < grid.resolution; ++z)
        for (int y = 0; y < grid.resolution; ++y)
            for (int x = 0; x < grid.resolution; ++x) {
                const std::size_t i = grid.index({x, y, z});
                if (injected.isZero(i)) continue;
                lit[bricks.index({x / kLanes, y / kLanes, z / kLanes})] = 1;
                for (const glm::vec4& c : {injected.r[i], injected.g[i], injected.b[i]})
                    lightSoFar += double(std::abs(c.x) + std::abs(c.y) + std::abs(c.z) + std::abs(c.w));
            }
    stats_.totalBricks = bricks.size();

    auto t0 = std::chrono::steady_clock::now();
    const bool sameGeometry = w.op && w.operatorOptions.occlusion == options.occlusion &&
                              w.operatorOptions.bounces == options.bounces &&
                              w.operatorGeometry.grid.resolution == geometry.grid.resolution &&
                              w.op->layout == layout && w.operatorGeometry.blocker == geometry.blocker &&
                              w.operatorGeometry.albedo == geometry.albedo;
    stats_.operatorBuilt = !sameGeometry;
    if (!sameGeometry) {
        w.op = std::make_unique<PropagationOperator>(geometry, grid, options);
        w.operatorGeometry = geometry;
        w.operatorOptions = options;
    }
    const PropagationOperator& op = *w.op;
    stats_.runs = op.bounce.size();
    stats_.occludedRuns = op.occludedRuns;
    stats_.bounceRuns = op.bounceRuns;
    auto t1 = std::chrono::steady_clock::now();
    stats_.operatorMs = std::chrono::duration<double, std::milli>(t1 - t0).count();

    // The bricks a step runs: those holding light and their face neighbours (light moves one
    // cell per step; bounces make a lit cell's own light feed back), every brick when dense.
    auto dilate = [&](const std::vector<std::uint8_t>& from, std::vector<std::uint8_t>& to) {
        std::size_t count = 0;
        for (int z = 0; z < bricks.count.z; ++z)
            for (int y = 0; y < bricks.count.y; ++y)
                for (int x = 0; x < bricks.count.x; ++x) {
                    const glm::ivec3 b(x, y, z);
                    bool on = !sparse || from[bricks.index(b)];
                    for (int a = 0; a < 6 && !on; ++a) {
                        const glm::ivec3 nbr = b + propagationTables().axes[std::size_t(a)];
                        on = bricks.contains(nbr) && from[bricks.index(nbr)];
                    }
                    to[bricks.index(b)] = on ? 1 : 0;
                    count += on ? 1 : 0;
                }
        return count;
    };
    // Each brick's output magnitude from its lane sums (lit: it sent light), and the step's total.
    auto sentLight = [&](const std::vector<float>& laneTotals, std::vector<std::uint8_t>& litOut) {
        double light = 0.0;
        for (std::size_t b = 0; b < bricks.size(); ++b) {
            float sent = 0.0f;
            for (int l = 0; l < kLanes; ++l) sent += laneTotals[b * kLanes + std::size_t(l)];
            litOut[b] = sent > 0.0f ? 1 : 0;
            light += double(sent);
        }
        return light;
    };
    const bool pairs = pairs_ == StepPairs::Always || (pairs_ == StepPairs::Auto && pairedPassFitsCache(layout));
    std::vector<std::uint8_t> active(bricks.size(), 0), secondActive(bricks.size(), 0), firstLit(bricks.size(), 0);
    std::vector<float> totals(bricks.size() * kLanes), secondTotals(bricks.size() * kLanes);
    std::vector<double> stepLight;  // each step's output, summed over bricks
    stats_.stepsRun = 0;
    // Records one step's light; true once propagation has converged.
    auto record = [&](double light) {
        lightSoFar += light;
        stepLight.push_back(light);
        ++stats_.stepsRun;
        return propagationConverged(stepLight, lightSoFar);
    };
    while (stats_.stepsRun < steps) {
        stats_.activeBricks = dilate(lit, active);
        // Bricks this step skips must not hold the light of two steps ago (their neighbours read it).
        for (std::size_t b = 0; b < bricks.size(); ++b)
            if (!active[b] && pongLit[b]) clearBrick(w.pong, bricks.brick(b));
        std::fill(totals.begin(), totals.end(), 0.0f);
        if (!pairs || steps - stats_.stepsRun < 2) {
            runStep(op, {&w.ping, &w.pong, &w.acc, nullptr, nullptr}, {bricks.count, active.data(), totals.data()});
            std::swap(w.ping, w.pong);
            pongLit = lit;
            if (record(sentLight(totals, lit))) break;
            continue;
        }
        // The second step may run every brick beside one the first ran: more than the bricks
        // its light reaches, which read zeros and write zeros, as a skipped brick holds.
        stats_.activeBricks = dilate(active, secondActive);
        std::fill(secondTotals.begin(), secondTotals.end(), 0.0f);
        runStepPair(op, {&w.ping, &w.pong, nullptr, nullptr, nullptr}, {bricks.count, active.data(), totals.data()},
                    {&w.pong, &w.ping, &w.acc, &w.pong, active.data()},
                    {bricks.count, secondActive.data(), secondTotals.data()});
        // ping holds the second step's output (the next input), pong the first's.
        const double firstLight = sentLight(totals, firstLit);
        const double secondLight = sentLight(secondTotals, lit);
        pongLit = firstLit;
        // A stop after the first step keeps the second's light, which the test bounds.
        const bool converged = record(firstLight);
        if (record(secondLight) || converged) break;
    }
    if (accumulated.r.size() != grid.cellCount()) accumulated.reset(grid);
    accumulated.grid = grid;
    w.acc.toVolume(accumulated);
    stats_.stepsMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count();
}

}  // namespace voxgi
