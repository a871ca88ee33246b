// LPV propagation (CPU reference): the derived face solid angles, exact flux conservation in
// empty space, inverse-square falloff, blocking by walls, bounded bounces and long runs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <utility>
#include <random>

#include "gi/lpv/detail/propagation_soa.h"
#include "gi/lpv/injection.h"
#include "gi/lpv/lpv_desc.h"
#include "gi/lpv/propagation.h"
#include "gi/sh/sh.h"
#include "shaders/shared/constants.h"

using namespace voxgi;

namespace {

glm::vec4 v4(const sh::Sh4& s) { return {s.c[0], s.c[1], s.c[2], s.c[3]}; }
sh::Sh4 sh4(glm::vec4 v) { return sh::Sh4{{v.x, v.y, v.z, v.w}}; }

double totalFlux(const LightVolume& lv, int channel) {
    const auto& data = channel == 0 ? lv.r : channel == 1 ? lv.g : lv.b;
    double sum = 0.0;
    for (const glm::vec4& c : data) sum += double(sh::integral(sh4(c)));
    return sum;
}

CascadeGrid unitGrid(int n, float cell = 1.0f) {
    CascadeGrid g;
    g.resolution = n;
    g.cellSize = cell;
    return g;
}

// An isotropic point source of intensity I (W/sr) in one cell: total flux 4 pi I.
void addIsotropic(LightVolume& lv, glm::ivec3 cell, float intensity) {
    glm::vec4 c(intensity / sh::kY00, 0, 0, 0);  // f(w) = I everywhere
    std::size_t i = lv.grid.index(cell);
    lv.r[i] += c;
    lv.g[i] += c;
    lv.b[i] += c;
}

// Irradiance on a surface at the centre of `cell` with normal n, radiance = I / h^2.
float irradiance(const LightVolume& lv, glm::ivec3 cell, glm::vec3 n) {
    float h = lv.grid.cellSize;
    return sh::convolveCosine(sh4(lv.r[lv.grid.index(cell)]), -n) / (h * h);
}

// A closed box of inward-facing, fully blocking walls of the given albedo one cell inside the grid.
BlockerVolume closedBox(const CascadeGrid& grid, float albedo) {
    const int n = grid.resolution;
    BlockerVolume box;
    box.reset(grid);
    for (int z = 0; z <= n; ++z)
        for (int y = 0; y <= n; ++y)
            for (int x = 0; x <= n; ++x) {
                glm::vec3 normal(0.0f);
                if (x == 1) normal.x += 1;
                if (x == n - 1) normal.x -= 1;
                if (y == 1) normal.y += 1;
                if (y == n - 1) normal.y -= 1;
                if (z == 1) normal.z += 1;
                if (z == n - 1) normal.z -= 1;
                if (normal == glm::vec3(0.0f)) continue;
                sh::Sh4 lobe = sh::cosineLobe(glm::normalize(normal));
                std::size_t i = box.cornerIndex({x, y, z});
                box.blocker[i] = v4(lobe) * (1.0f / sh::evaluate(lobe, glm::normalize(normal)));
                box.albedo[i] = glm::vec3(albedo);
            }
    return box;
}

}  // namespace

TEST(LpvPropagation, FaceSolidAnglesAreDerivedExactly) {
    const PropagationTables& t = propagationTables();
    EXPECT_NEAR(t.frontSolidAngle, 0.4006696846, 1e-7);
    EXPECT_NEAR(t.sideSolidAngle, 0.4234313544, 1e-7);  // not the 0.4234413544 found in public code
    EXPECT_NEAR(std::asin(0.1) * 4.0, 0.4006696846, 1e-9);
    // The 5 faces of the next cell cover the shared face: 2 pi / 3 (a sixth of the sphere).
    for (const auto& faces : t.faces) {
        double sum = 0.0;
        for (const auto& f : faces) sum += f.solidAngle;
        EXPECT_NEAR(sum, 2.0 * shading::kPiDouble / 3.0, 1e-6);
    }
}

TEST(LpvPropagation, OneStepInEmptySpaceConservesFlux) {
    LightVolume in;
    in.reset(unitGrid(16));
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int k = 0; k < 40; ++k) {
        glm::ivec3 cell(4 + int(rng() % 8), 4 + int(rng() % 8), 4 + int(rng() % 8));
        glm::vec3 n = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        std::size_t i = in.grid.index(cell);
        in.r[i] += v4(sh::cosineLobe(n)) * 2.0f;
        in.g[i] += v4(sh::basis(n)) * 0.5f + glm::vec4(1.0f, 0, 0, 0);  // arbitrary SH with positive mean
        in.b[i] += v4(sh::cosineLobe(-n)) * 1e-3f;
    }
    LightVolume out;
    BlockerVolume empty;
    empty.reset(in.grid);
    CpuPropagator::step(in, empty, {}, out);
    for (int c = 0; c < 3; ++c) {
        double before = totalFlux(in, c), after = totalFlux(out, c);
        EXPECT_NEAR(after / before, 1.0, 1e-5) << "channel " << c;
    }
}

TEST(LpvPropagation, PointSourceFallsOffAsInverseSquare) {
    // Once enough steps have run for light to settle (the 5-face reprojection is diffusive:
    // 16 steps carry light about 5 cells), E r^2 is flat within 10 % from 4 cells out to where
    // the grid border starts to drain it, along the axes and the diagonals.
    const int n = 48;
    LightVolume in, acc;
    in.reset(unitGrid(n));
    glm::ivec3 src(n / 2);
    addIsotropic(in, src, 1.0f);
    BlockerVolume empty;
    empty.reset(in.grid);
    CpuPropagator p;
    p.propagate(in, empty, 200, {}, acc);
    std::vector<float> scaled;
    for (int r = 4; r <= 10; ++r)
        for (const glm::ivec3& axis : propagationTables().axes)
            scaled.push_back(irradiance(acc, src + axis * r, -glm::vec3(axis)) * float(r * r));
    for (int d = 3; d <= 6; ++d) {  // body diagonal, r = d sqrt(3)
        glm::ivec3 cell = src + glm::ivec3(d);
        scaled.push_back(irradiance(acc, cell, -glm::normalize(glm::vec3(1))) * float(3 * d * d));
    }
    float mean = 0.0f;
    for (float s : scaled) mean += s / float(scaled.size());
    for (float s : scaled) EXPECT_NEAR(s / mean, 1.0f, 0.10f);
}

TEST(LpvPropagation, BlockerWallStopsTheFluxCrossingIt) {
    const int n = 24;
    LightVolume in, open, walled;
    in.reset(unitGrid(n));
    addIsotropic(in, {6, 12, 12}, 1.0f);
    BlockerVolume empty, wall;
    empty.reset(in.grid);
    wall.reset(in.grid);
    // A full wall on the plane x = 10 (corner index 10) facing the source (-x): blocker
    // B(w) = max(0, -w.x) scaled so that it blocks fully along its normal.
    sh::Sh4 lobe = sh::cosineLobe(glm::vec3(-1, 0, 0));
    float peak = sh::evaluate(lobe, glm::vec3(-1, 0, 0));
    for (int z = 0; z <= n; ++z)
        for (int y = 0; y <= n; ++y) {
            std::size_t i = wall.cornerIndex({10, y, z});
            wall.blocker[i] = v4(lobe) * (1.0f / peak);
            wall.albedo[i] = glm::vec3(0.0f);
        }
    CpuPropagator p;
    PropagationOptions opt;
    p.propagate(in, empty, 30, opt, open);
    p.propagate(in, wall, 30, opt, walled);
    auto beyond = [&](const LightVolume& lv) {
        double sum = 0.0;
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 10; x < n; ++x) sum += sh::integral(sh4(lv.r[lv.grid.index({x, y, z})]));
        return sum;
    };
    double ratio = beyond(walled) / beyond(open);
    EXPECT_LT(ratio, 0.10) << "flux behind the wall relative to open space";
    EXPECT_GE(ratio, -0.01);
}

TEST(LpvPropagation, EachBounceCarriesAtMostAlbedoTimesIncoming) {
    // A closed box of inward-facing walls with albedo 0.9: every step's total flux is at most
    // 0.9 of the previous one once light has reached the walls, and never grows.
    const int n = 8;
    LightVolume in;
    in.reset(unitGrid(n));
    addIsotropic(in, {4, 4, 4}, 1.0f);
    const BlockerVolume box = closedBox(in.grid, 0.9f);
    LightVolume a = in, b;
    double previous = totalFlux(a, 0);
    for (int s = 0; s < 60; ++s) {
        CpuPropagator::step(a, box, {}, b);
        double now = totalFlux(b, 0);
        ASSERT_TRUE(std::isfinite(now));
        EXPECT_LE(now, previous * (1.0 + 1e-5)) << "step " << s;
        previous = now;
        std::swap(a, b);
    }
    EXPECT_LT(previous, totalFlux(in, 0) * 0.9);
}

TEST(LpvPropagation, ThousandStepsStayBoundedAndFinite) {
    const int n = 16;
    LightVolume in, acc;
    in.reset(unitGrid(n));
    addIsotropic(in, {8, 8, 8}, 1e6f);
    BlockerVolume gv;
    gv.reset(in.grid);
    // Random blockers with albedo close to 1 everywhere: the stiff case.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (std::size_t i = 0; i < gv.blocker.size(); i += 3) {
        glm::vec3 nrm = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + 1e-3f);
        sh::Sh4 lobe = sh::cosineLobe(nrm);
        gv.blocker[i] = v4(lobe) * (0.99f / sh::evaluate(lobe, nrm));
        gv.albedo[i] = glm::vec3(0.999f);
    }
    CpuPropagator p;
    p.propagate(in, gv, 1000, {}, acc);
    double injected = totalFlux(in, 0);
    for (const glm::vec4& c : acc.r) ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.w));
    // The accumulated light is a Neumann series of a contraction: bounded by a few times the
    // injected flux times the number of cells light can cross.
    EXPECT_LT(std::abs(totalFlux(acc, 0)), injected * 1000.0);
}

TEST(LpvPropagation, ConvergenceTestBoundsTheGeometricTail) {
    // Each step sends q times the light of the one before: the light still to come after step
    // k is exactly q^(k+1) / (1 - q), and propagation stops at the first step where that falls
    // below kConvergenceTolerance of the light so far.
    const double q = 0.99;
    std::vector<double> steps;
    double soFar = 1.0;
    int stopped = -1;
    for (int k = 0; k < 5000 && stopped < 0; ++k) {
        steps.push_back(std::pow(q, k + 1));
        soFar += steps.back();
        if (propagationConverged(steps, soFar)) stopped = k;
    }
    ASSERT_GT(stopped, 0);
    auto tail = [&](int k) { return std::pow(q, k + 2) / (1.0 - q); };
    auto total = [&](int k) { return 1.0 + q * (1.0 - std::pow(q, k + 1)) / (1.0 - q); };
    EXPECT_LT(tail(stopped), kConvergenceTolerance * total(stopped) * 1.0001);
    EXPECT_GE(tail(stopped - 1), kConvergenceTolerance * total(stopped - 1) * 0.9999);
    // Light that is not decaying never counts as converged; no light left always does.
    EXPECT_FALSE(propagationConverged(std::vector<double>(100, 1e-12), 1.0));
    EXPECT_TRUE(propagationConverged({1.0, 0.0}, 2.0));
}

TEST(LpvPropagation, ManyStepsStopOnceConvergedWithTheLightOfEveryStep) {
    // A closed box with albedo 0.9: light bounces for thousands of steps. Asking for 100000
    // stops early, and the result matches summing single steps until the light is gone.
    const int n = 8;
    LightVolume in, acc;
    in.reset(unitGrid(n));
    addIsotropic(in, {4, 4, 4}, 1.0f);
    const BlockerVolume box = closedBox(in.grid, 0.9f);
    CpuPropagator p;
    p.propagate(in, box, 100000, {}, acc);
    EXPECT_LT(p.stats().stepsRun, 20000);
    EXPECT_GT(p.stats().stepsRun, 16);

    LightVolume a = in, b;
    double all = totalFlux(in, 0);
    for (int s = 0; s < 100000; ++s) {
        CpuPropagator::step(a, box, {}, b);
        const double sent = totalFlux(b, 0);
        all += sent;
        if (std::abs(sent) < 1e-9 * std::abs(all)) break;
        std::swap(a, b);
    }
    EXPECT_NEAR(totalFlux(acc, 0), all, 1e-4 * std::abs(all));
}

TEST(LpvPropagation, FittedStepsCarryLightAcrossTheCascade) {
    // Light moves one cell per step: "fit" (the default) runs as many steps as the cascade has
    // cells per side, so light injected at one face reaches the opposite one.
    GiSettings gi;
    gi.set("lpv.resolution", "24");
    const LpvDesc fitted = readLpvDesc(gi, true);
    EXPECT_EQ(fitted.steps, kFittedInteger);
    EXPECT_EQ(propagationSteps(fitted), 24);
    gi.set("lpv.steps", "7");
    EXPECT_EQ(propagationSteps(readLpvDesc(gi, true)), 7);
    gi.set("lpv.steps", "fit");
    EXPECT_EQ(propagationSteps(readLpvDesc(gi, false)), 24);

    const int n = 24;
    LightVolume in, acc;
    in.reset(unitGrid(n));
    addIsotropic(in, {0, n / 2, n / 2}, 1.0f);
    BlockerVolume empty;
    empty.reset(in.grid);
    CpuPropagator p;
    const glm::ivec3 far(n - 1, n / 2, n / 2);
    p.propagate(in, empty, n - 2, {}, acc);
    EXPECT_EQ(irradiance(acc, far, {-1, 0, 0}), 0.0f) << "light travels at most one cell per step";
    p.propagate(in, empty, propagationSteps(fitted), {}, acc);
    EXPECT_GT(irradiance(acc, far, {-1, 0, 0}), 0.0f);
}

TEST(LpvPropagation, SparseMatchesDense) {
    const int n = 32;
    LightVolume in, sparse, dense;
    in.reset(unitGrid(n));
    addIsotropic(in, {5, 6, 7}, 2.0f);
    addIsotropic(in, {25, 20, 9}, 0.5f);
    BlockerVolume gv;
    gv.reset(in.grid);
    for (int y = 0; y <= n; ++y)
        for (int z = 0; z <= n; ++z) {
            sh::Sh4 lobe = sh::cosineLobe({0, 0, 1});
            gv.blocker[gv.cornerIndex({12, y, z})] = v4(lobe) * 0.8f;
            gv.albedo[gv.cornerIndex({12, y, z})] = glm::vec3(0.5f);
        }
    CpuPropagator p;
    p.propagate(in, gv, 12, {}, sparse, true);
    p.propagate(in, gv, 12, {}, dense, false);
    for (std::size_t i = 0; i < dense.r.size(); ++i)
        for (int k = 0; k < 4; ++k) ASSERT_NEAR(sparse.r[i][k], dense.r[i][k], 1e-6f * (1.0f + std::abs(dense.r[i][k])));
}

// The step's SIMD variants (AVX-512VL, AVX2 + FMA, SSE) run the same arithmetic: every one the
// CPU supports must give the baseline's light, including partial runs (resolution 12).
TEST(LpvPropagation, EverySimdPathGivesTheSameStep) {
    using namespace lpv_detail;
    for (int n : {12, 16}) {
        LightVolume in;
        in.reset(unitGrid(n));
        BlockerVolume gv;
        gv.reset(in.grid);
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(-1.0f, 1.0f);
        for (int k = 0; k < 3 * n; ++k) {
            std::size_t i = std::size_t(rng() % in.grid.cellCount());
            glm::vec4 lobe = v4(sh::cosineLobe(glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + 1e-3f)));
            in.r[i] += lobe * 2.0f;
            in.g[i] += lobe;
            in.b[i] += lobe * 0.5f;
        }
        for (std::size_t i = 0; i < gv.blocker.size(); i += 5) {
            gv.blocker[i] = fullBlocker(glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + 1e-3f)) * std::abs(u(rng));
            gv.albedo[i] = glm::vec3(0.9f, 0.6f, 0.3f);
        }
        const SoaLayout layout(n);
        const PropagationOperator op(gv, in.grid, {});
        SoaLight from;
        from.reset(layout);
        from.fromVolume(in);
        auto run = [&](SimdLevel level) {
            SoaLight to, acc;
            to.reset(layout);
            acc.reset(layout);
            const int bricks = (n + kLanes - 1) / kLanes;
            const std::vector<std::uint8_t> active(std::size_t(layout.runsX * bricks * bricks), 1);
            std::vector<float> totals(active.size() * kLanes);
            for (int z = 0; z < n; ++z)
                propagateRows(op, {&from, &to, &acc, nullptr, nullptr}, {{layout.runsX, bricks, bricks}, active.data(), totals.data()},
                              z, 0, n, level);
            return to.data;
        };
        const std::vector<float> baseline = run(SimdLevel::Baseline);
        float scale = 0.0f;
        for (float v : baseline) scale = std::max(scale, std::abs(v));
        ASSERT_GT(scale, 0.0f);
        int compared = 0;
        for (SimdLevel level : {SimdLevel::Avx2, SimdLevel::Avx512}) {
            if (!simdLevelSupported(level)) continue;
            ++compared;
            const std::vector<float> other = run(level);
            for (std::size_t i = 0; i < baseline.size(); ++i)
                ASSERT_NEAR(other[i], baseline[i], 1e-6f * scale) << "n " << n << " level " << int(level) << " at " << i;
        }
        std::printf("n %d: compared %d SIMD variant(s) with the baseline\n", n, compared);
    }
}

// Two steps per pass through memory (large cascades) give single steps' light to the bit, sparse
// or dense, with an odd step count (a single step last), blockers and bounces, and partial runs;
// a propagation that converges agrees to its tolerance.
TEST(LpvPropagation, PairedStepsGiveTheLightOfSingleSteps) {
    const int n = 20;
    LightVolume in;
    in.reset(unitGrid(n));
    addIsotropic(in, {3, 4, 5}, 1.0f);
    addIsotropic(in, {15, 12, 9}, 0.25f);
    const BlockerVolume box = closedBox(in.grid, 0.9f);
    for (bool sparse : {true, false})
        for (int steps : {7, 8}) {
            LightVolume single, paired;
            CpuPropagator a, b;
            a.setStepPairs(CpuPropagator::StepPairs::Never);
            b.setStepPairs(CpuPropagator::StepPairs::Always);
            a.propagate(in, box, steps, {}, single, sparse);
            b.propagate(in, box, steps, {}, paired, sparse);
            EXPECT_EQ(a.stats().stepsRun, steps);
            EXPECT_EQ(b.stats().stepsRun, steps);
            ASSERT_GT(totalFlux(single, 0), totalFlux(in, 0));
            for (const auto& [x, y] : {std::pair{&single.r, &paired.r}, {&single.g, &paired.g}, {&single.b, &paired.b}})
                ASSERT_TRUE(std::memcmp(x->data(), y->data(), x->size() * sizeof(glm::vec4)) == 0)
                    << "sparse " << sparse << ", " << steps << " steps";
        }
    LightVolume single, paired;
    CpuPropagator a, b;
    a.setStepPairs(CpuPropagator::StepPairs::Never);
    b.setStepPairs(CpuPropagator::StepPairs::Always);
    a.propagate(in, box, 100000, {}, single);
    b.propagate(in, box, 100000, {}, paired);
    EXPECT_LE(std::abs(b.stats().stepsRun - a.stats().stepsRun), 1);
    EXPECT_NEAR(totalFlux(paired, 0), totalFlux(single, 0), 1e-5 * totalFlux(single, 0));
}
