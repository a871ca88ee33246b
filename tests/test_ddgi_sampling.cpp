// ProbeSampler's SIMD path against the scalar reference: random fields that reach every edge
// case of the cage (off probes, one-probe dimensions, zero and negative variance, points on a
// probe, all weights zero, cascades, other gammas) and a converged field of a real scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "gi/ddgi/ddgi_system.h"
#include "gi/ddgi/probe_sampling.h"
#include "gi/octahedral/octahedral.h"
#include "gi/raytrace/ray_tracer.h"
#include "test_ddgi_scenes.h"

using namespace voxgi;

namespace {

// The cage weights are identical on both paths; only the order of the weighted sums differs
// (measured differences stay under 1e-6).
constexpr float kTolerance = 1e-5f;

bool cpuHasAvx2() {
#if defined(__x86_64__)
    return __builtin_cpu_supports("avx2");
#else
    return false;
#endif
}

// Relative agreement, with `floor` as the smallest magnitude compared relatively.
::testing::AssertionResult agree(glm::vec4 a, glm::vec4 b, float rel, float floor) {
    for (int k = 0; k < 4; ++k) {
        float scale = std::max({std::abs(a[k]), std::abs(b[k]), floor});
        if (!(std::abs(a[k] - b[k]) <= rel * scale))
            return ::testing::AssertionFailure() << "channel " << k << ": " << a[k] << " vs " << b[k];
    }
    return ::testing::AssertionSuccess();
}

glm::vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> g;
    for (;;) {
        glm::vec3 v(g(rng), g(rng), g(rng));
        float l = glm::length(v);
        if (l > 1e-3f) return v / l;
    }
}

std::vector<ProbeVolume> stackVolumes(std::vector<ProbeVolume> volumes) {
    int probeBase = 0, tileRow = 0;
    for (ProbeVolume& v : volumes) {
        v.probeBase = probeBase;
        v.tileRow = tileRow;
        probeBase += v.probeCount();
        tileRow += v.counts.y;
    }
    return volumes;
}

// Random atlases: some tiles constant (zero variance), some texels with meanSquare < mean^2,
// negative irradiance (clamped by the decode), some probes off, probes relocated.
void randomize(ProbeField& f, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (glm::vec4& t : f.irradiance.texels) t = glm::vec4(u(rng) * 2.0f - 0.2f, u(rng), u(rng) * 3.0f, u(rng));
    const int tileD = f.distance.tile;
    const std::size_t tileTexels = std::size_t(tileD * tileD);
    for (std::size_t tile = 0; tile * tileTexels < f.distance.texels.size(); ++tile) {
        float kind = u(rng);
        for (std::size_t i = 0; i < tileTexels; ++i) {
            float mean = 0.2f + 1.5f * u(rng);
            float variance = kind < 0.2f ? 0.0f : kind < 0.3f ? -0.05f * u(rng) : 0.3f * u(rng) * u(rng);
            if (kind < 0.2f) mean = 0.8f;
            f.distance.texels[tile * tileTexels + i] = glm::vec4(mean, mean * mean + variance, 0.0f, 0.0f);
        }
    }
    if (f.occlusion.texels.empty()) f.occlusion.resize(f.distance.width / tileD, f.distance.height / tileD, tileD, glm::vec4(1.0f));
    for (glm::vec4& t : f.occlusion.texels) t = glm::vec4(u(rng), u(rng), u(rng), u(rng));
    for (int p = 0; p < f.probeCount(); ++p) {
        ProbeRecord& rec = f.probes[std::size_t(p)];
        const ProbeVolume& v = f.volumes()[std::size_t(f.volumeOf(p))];
        rec.offset = (glm::vec3(u(rng), u(rng), u(rng)) - 0.5f) * 0.9f * v.spacing;
        rec.state = u(rng) < 0.15f ? ProbeState::Off : ProbeState::Active;
    }
}

struct Counts {
    int compared = 0, zeroWeight = 0, partial = 0;
    float maxRelative = 0.0f;  // irradiance, over channels above 1e-6
};

// Both samplers at `points` random points in and around every volume and at every probe.
Counts compareSamplers(const ProbeField& field, std::mt19937& rng, int points) {
    const ProbeSampler scalar(field, SamplingPath::Scalar), fast(field, SamplingPath::Avx2);
    EXPECT_EQ(fast.path(), SamplingPath::Avx2);
    std::uniform_real_distribution<float> u(-0.3f, 1.3f);
    Counts counts;
    auto check = [&](glm::vec3 p, glm::vec3 n, glm::vec3 toViewer) {
        for (int v = 0; v < int(field.volumes().size()); ++v) {
            float ws = -2.0f, wf = -3.0f;
            glm::vec3 a = scalar.volumeIrradiance(v, p, n, toViewer, &ws);
            glm::vec3 b = fast.volumeIrradiance(v, p, n, toViewer, &wf);
            // Weights are compared relative to a full weight (about 1 per probe).
            ASSERT_TRUE(agree(glm::vec4(ws), glm::vec4(wf), kTolerance, 1e-2f)) << "weight sum, volume " << v;
            ASSERT_TRUE(agree(glm::vec4(a, 0.0f), glm::vec4(b, 0.0f), kTolerance, 1e-6f)) << "volume " << v;
            for (int k = 0; k < 3; ++k)
                if (std::max(a[k], b[k]) > 1e-6f)
                    counts.maxRelative = std::max(counts.maxRelative, std::abs(a[k] - b[k]) / std::max(a[k], b[k]));
            counts.zeroWeight += ws == 0.0f;
            counts.partial += ws > 0.0f && ws < 0.5f;
            ++counts.compared;
        }
        ASSERT_TRUE(agree(glm::vec4(scalar.irradiance(p, n, toViewer), 0.0f), glm::vec4(fast.irradiance(p, n, toViewer), 0.0f),
                          kTolerance, 1e-6f));
        ASSERT_TRUE(agree(scalar.occlusion(p, n), fast.occlusion(p, n), kTolerance, 1e-6f));
    };
    for (const ProbeVolume& v : field.volumes()) {
        glm::vec3 extent = glm::vec3(glm::max(v.counts - 1, glm::ivec3(1))) * v.spacing;
        for (int i = 0; i < points; ++i) {
            glm::vec3 p = v.origin + glm::vec3(u(rng), u(rng), u(rng)) * extent;
            check(p, randomUnit(rng), randomUnit(rng));
            if (::testing::Test::HasFatalFailure()) return counts;
        }
    }
    for (int probe = 0; probe < field.probeCount(); ++probe) {
        check(field.probePosition(probe), randomUnit(rng), randomUnit(rng));
        if (::testing::Test::HasFatalFailure()) return counts;
    }
    return counts;
}

}  // namespace

TEST(DdgiSampling, TheSimdPathIsChosenWhereTheCpuHasIt) {
    EXPECT_TRUE(samplingPathSupported(SamplingPath::Scalar));
    EXPECT_EQ(samplingPathSupported(SamplingPath::Avx2), cpuHasAvx2());
    ProbeField field(DdgiDesc{}, stackVolumes({ProbeVolume{}}));
    EXPECT_EQ(ProbeSampler(field).path(), cpuHasAvx2() ? SamplingPath::Avx2 : SamplingPath::Scalar);
    EXPECT_EQ(ProbeSampler(field, SamplingPath::Scalar).path(), SamplingPath::Scalar);
    if (!cpuHasAvx2()) {
        EXPECT_THROW(ProbeSampler(field, SamplingPath::Avx2), std::logic_error);
    }
}

TEST(DdgiSampling, SimdMatchesScalarOnRandomFields) {
    if (!cpuHasAvx2()) GTEST_SKIP() << "no AVX2 on this CPU";
    std::mt19937 rng(7);
    auto volume = [](glm::ivec3 counts, glm::vec3 spacing, glm::vec3 origin, glm::ivec3 scroll) {
        ProbeVolume v;
        v.counts = counts;
        v.spacing = spacing;
        v.origin = origin;
        v.scroll = scroll;
        return v;
    };
    Counts total;
    // Gamma 5 (x^2.5), 2 (no decode) and 3 (pow); with and without bias (points on probes).
    for (float gamma : {5.0f, 2.0f, 3.0f})
        for (float bias : {0.1f, 0.0f}) {
            DdgiDesc desc;
            desc.irradianceGamma = gamma;
            desc.normalBias = desc.viewBias = bias;
            desc.distanceTexels = gamma == 3.0f ? 8 : 16;
            desc.irradianceTexels = gamma == 3.0f ? 6 : 8;
            ProbeField field(desc, stackVolumes({volume({4, 3, 5}, {0.5f, 0.7f, 0.4f}, {-1.0f, 0.2f, -0.8f}, {1, 2, 3}),
                                                 volume({3, 1, 2}, {1.0f, 1.0f, 2.0f}, {-2.0f, -1.0f, -2.0f}, {0, 0, 1}),
                                                 volume({1, 1, 1}, {2.0f, 2.0f, 2.0f}, {0.0f, 0.0f, 0.0f}, {0, 0, 0})}));
            randomize(field, rng);
            Counts c = compareSamplers(field, rng, 1500);
            if (HasFatalFailure()) return;
            total.compared += c.compared;
            total.zeroWeight += c.zeroWeight;
            total.partial += c.partial;
            total.maxRelative = std::max(total.maxRelative, c.maxRelative);
        }
    // The edge cases were reached: cages without any live probe and cages of low weight.
    EXPECT_GT(total.zeroWeight, 0);
    EXPECT_GT(total.partial, 0);
    std::printf("compared %d cages: %d without weight, %d with weight sum < 0.5; max relative difference %.2e\n",
                total.compared, total.zeroWeight, total.partial, total.maxRelative);

    // Every probe off: both give zero irradiance, no occlusion data, weight sum 0.
    ProbeField off(DdgiDesc{}, stackVolumes({volume({2, 2, 2}, glm::vec3(1.0f), glm::vec3(0.0f), glm::ivec3(0))}));
    for (ProbeRecord& r : off.probes) r.state = ProbeState::Off;
    for (SamplingPath path : {SamplingPath::Scalar, SamplingPath::Avx2}) {
        ProbeSampler s(off, path);
        float w = -1.0f;
        EXPECT_EQ(s.volumeIrradiance(0, glm::vec3(0.4f), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0), &w), glm::vec3(0.0f));
        EXPECT_EQ(w, 0.0f);
    }
}

TEST(DdgiSampling, SimdMatchesScalarOnAConvergedField) {
    if (!cpuHasAvx2()) GTEST_SKIP() << "no AVX2 on this CPU";
    // Two rooms and a thin wall, a probe plane in it: relocation moves probes, classification
    // may turn some off, and light differs sharply across the wall.
    Scene scene = test::twoRooms();
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, test::descFrom({{"probes", "7,3,3"}, {"rays", "128"}, {"hysteresis", "0.5"}, {"hit_cache", "off"}}));
    for (int i = 0; i < 16; ++i) ddgi.update(glm::vec3(-1.5f, 0.0f, 0.0f));
    std::mt19937 rng(11);
    Counts c = compareSamplers(ddgi.field(), rng, 3000);
    std::printf("compared %d cages; max relative difference %.2e\n", c.compared, c.maxRelative);
}
