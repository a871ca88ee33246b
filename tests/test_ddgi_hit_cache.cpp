// The DDGI hit cache (gi/ddgi/hit_cache.h): grouping rules, order independence, and the error
// of cached probe-ray shading against exact shading of the same rays on the same field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <random>

#include "gi/ddgi/ddgi_system.h"
#include "gi/ddgi/hit_cache.h"
#include "gi/ddgi/probe_sampling.h"
#include "gi/raytrace/ray_tracer.h"
#include "test_ddgi_scenes.h"

using namespace voxgi;

namespace {

struct Hit {
    glm::vec3 position, normal;
};

// Groups `hits` (one run) with 1 m cells.
void group(HitCache& cache, const std::vector<Hit>& hits) {
    cache.group(1.0f, 1, hits.size(), [&](std::size_t, std::size_t i, glm::vec3* p, glm::vec3* n) {
        *p = hits[i].position;
        *n = hits[i].normal;
        return true;
    });
}

}  // namespace

TEST(DdgiHitCache, GroupsByCellAndNormalBin) {
    const glm::vec3 up(0, 1, 0), down(0, -1, 0);
    std::vector<Hit> hits = {
        {{0.2f, 0.5f, 0.3f}, up},    // 0: cell (0,0,0), up
        {{0.6f, 0.5f, 0.4f}, up},    // 1: same cell, same bin -> shares with 0
        {{0.5f, 0.5f, 0.5f}, down},  // 2: same cell, other face of a thin wall -> its own group
        {{1.2f, 0.5f, 0.3f}, up},    // 3: next cell
        {{0.45f, 0.52f, 0.5f}, up},  // 4: same cell as 0, closest to the centre -> representative
    };
    HitCache cache;
    group(cache, hits);
    EXPECT_EQ(cache.groups(), 3u);
    EXPECT_EQ(cache.groupOf(0), cache.groupOf(1));
    EXPECT_EQ(cache.groupOf(0), cache.groupOf(4));
    EXPECT_NE(cache.groupOf(0), cache.groupOf(2));
    EXPECT_NE(cache.groupOf(0), cache.groupOf(3));
    EXPECT_EQ(cache.representative(cache.groupOf(1)), 4u);
    EXPECT_EQ(cache.representative(cache.groupOf(2)), 2u);
}

TEST(DdgiHitCache, RepresentativesDoNotDependOnHitOrder) {
    // Many hits on a few planes; shuffled, the same points represent the same groups, also
    // when the table has to grow mid-frame (a fresh cache starts small).
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-4.0f, 4.0f);
    std::vector<Hit> hits;
    for (int i = 0; i < 20000; ++i) {
        glm::vec3 p(u(rng), u(rng), u(rng));
        glm::vec3 n = i % 3 == 0 ? glm::vec3(1, 0, 0) : i % 3 == 1 ? glm::vec3(0, 0.6f, 0.8f) : glm::vec3(0, 0, -1);
        hits.push_back({p, n});
    }
    auto representatives = [](const std::vector<Hit>& h) {
        HitCache cache;
        group(cache, h);
        std::vector<std::pair<float, float>> points;  // (x, y) of each representative, sorted
        for (std::size_t g = 0; g < cache.groups(); ++g) {
            const Hit& r = h[cache.representative(g)];
            points.emplace_back(r.position.x, r.position.y + 10.0f * r.normal.y + 100.0f * r.normal.z);
        }
        std::sort(points.begin(), points.end());
        return points;
    };
    auto a = representatives(hits);
    std::shuffle(hits.begin(), hits.end(), rng);
    auto b = representatives(hits);
    EXPECT_GT(a.size(), 1000u);
    EXPECT_EQ(a, b);
}

namespace {

// Sum over probes and channels of |a - b| in mean irradiance, over the sum of a's.
double fieldDifference(const ProbeField& a, const ProbeField& b) {
    double sum = 0, diff = 0;
    for (int p = 0; p < a.probeCount(); ++p) {
        glm::vec3 x = a.meanIrradiance(p), y = b.meanIrradiance(p);
        sum += x.x + x.y + x.z;
        diff += std::abs(x.x - y.x) + std::abs(x.y - y.y) + std::abs(x.z - y.z);
    }
    return diff / sum;
}

// A copy of `source`'s field state under another desc (another hit-cache mode).
std::unique_ptr<ProbeField> fieldWith(const ProbeField& source, const DdgiDesc& desc) {
    auto f = std::make_unique<ProbeField>(desc, source.volumes());
    f->irradiance = source.irradiance;
    f->distance = source.distance;
    f->probes = source.probes;
    return f;
}

struct ShadingError {
    double meanRelative = 0;  // mean over rays of |cached - exact|, over the mean exact radiance
    double probeMean = 0;     // largest |difference| of a probe's mean radiance, over the mean
};

// Shades the last frame's rays of `ddgi` against its field exactly and with `mode`.
ShadingError compareShading(const Scene& scene, const DdgiSystem& ddgi, const std::string& mode, int cells) {
    const ProbeField& field = ddgi.field();
    DdgiDesc exactDesc = field.desc(), cachedDesc = field.desc();
    exactDesc.hitCache = DdgiHitCache::Off;
    cachedDesc.hitCache = mode == "all" ? DdgiHitCache::All : DdgiHitCache::Probes;
    cachedDesc.hitCacheCells = cells;
    auto exactField = fieldWith(field, exactDesc), cachedField = fieldWith(field, cachedDesc);
    ProbeSampler exactSampler(*exactField), cachedSampler(*cachedField);
    ShadowRayVisibility shadows(ddgi.tracer(), 1e-4f);
    std::vector<int> probes(std::size_t(field.probeCount()));
    std::iota(probes.begin(), probes.end(), 0);
    ShadedRays exact, cached;
    HitCache cache;
    groupProbeHits(cache, *cachedField, ddgi.lastRays(), ddgi.lastTrace());
    shadeProbeRays(scene, shadows, exactSampler, ddgi.lastRays(), ddgi.lastTrace(), probes, 7, nullptr, exact);
    ShadeStats stats =
        shadeProbeRays(scene, shadows, cachedSampler, ddgi.lastRays(), ddgi.lastTrace(), probes, 7, &cache, cached);
    EXPECT_GT(stats.cachedHits, 0);
    EXPECT_LT(stats.cacheGroups * 2, stats.cachedHits);  // the cache shares
    double sum = 0, diff = 0, worstProbe = 0;
    const int perProbe = exact.raysPerJob;
    for (std::size_t p = 0; p < probes.size(); ++p) {
        double a = 0, b = 0;
        for (int i = 0; i < perProbe; ++i) {
            const glm::vec4 &x = exact.values[p * std::size_t(perProbe) + std::size_t(i)],
                            &y = cached.values[p * std::size_t(perProbe) + std::size_t(i)];
            EXPECT_EQ(x.w, y.w);  // same hits
            if (x.w < 0.0f || x.w >= kMissDistance) continue;
            a += x.x + x.y + x.z;
            b += y.x + y.y + y.z;
            diff += std::abs(x.x - y.x) + std::abs(x.y - y.y) + std::abs(x.z - y.z);
        }
        sum += a;
        worstProbe = std::max(worstProbe, std::abs(a - b));
    }
    const double meanProbe = sum / double(probes.size());
    return {diff / sum, worstProbe / meanProbe};
}

}  // namespace

TEST(DdgiHitCache, CachedShadingStaysCloseToExactShading) {
    // The yard: a point light, blocks casting shadows and a sky. The field is converged with
    // exact shading; then one frame's rays are shaded against it exactly and with the cache.
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, test::descFrom({{"probes", "6,3,6"}, {"spacing", "0.6"}, {"rays", "128"},
                                            {"hysteresis", "0.5"}, {"classify", "false"}, {"relocate", "false"}}));
    for (int f = 0; f < 20; ++f) ddgi.update(glm::vec3(0.0f));
    for (int cells : {4, 2, 1})
        for (const char* mode : {"probes", "all"}) {
            ShadingError e = compareShading(scene, ddgi, mode, cells);
            std::printf("hit cache %s, %d cells per spacing, vs exact: mean per-ray radiance error %.2f %%, worst "
                        "probe mean %.2f %%\n",
                        mode, cells, 100.0 * e.meanRelative, 100.0 * e.probeMean);
            if (cells != 2) continue;  // the default; the others are printed for docs/ddgi.md
            const bool all = mode == std::string("all");
            // Measured: probes 0.33 % / 3.9 %, all 3.7 % / 7.0 %. In the `all` mode a hit takes
            // the light's direction, distance and visibility from its group's representative
            // (shadow edges snap to the cells, and a ray's irradiance is off by the cell's
            // fall-off); a probe averages over its rays, which is what the second bound checks.
            EXPECT_LT(e.meanRelative, all ? 0.05 : 0.01) << mode;
            EXPECT_LT(e.probeMean, all ? 0.12 : 0.06) << mode;
        }
}

TEST(DdgiHitCache, ConvergedFieldStaysCloseToTheExactField) {
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    auto run = [&](const char* mode) {
        auto d = std::make_unique<DdgiSystem>(
            tracer, test::descFrom({{"probes", "6,3,6"}, {"spacing", "0.6"}, {"rays", "128"}, {"hysteresis", "0.8"},
                                    {"relocate", "false"}, {"hit_cache", mode}}));
        for (int f = 0; f < 40; ++f) d->update(glm::vec3(0.0f));
        return d;
    };
    auto exact = run("off");
    for (const char* mode : {"probes", "all"}) {
        auto cached = run(mode);
        const double difference = fieldDifference(exact->field(), cached->field());
        std::printf("hit cache %s: converged probe irradiance differs from exact shading by %.2f %% (mean |diff|)\n",
                    mode, 100.0 * difference);
        EXPECT_LT(difference, 0.05) << mode;
    }
}

TEST(DdgiHitCache, GroupingWhileTracingMatchesGroupingAfterwards) {
    // traceProbes adds hits from TBB tasks into per-thread tables as they are traced; grouping
    // the finished trace must give the same groups and representatives.
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, test::descFrom({{"probes", "6,3,6"}, {"spacing", "0.6"}, {"rays", "128"}}));
    for (int f = 0; f < 3; ++f) ddgi.update(glm::vec3(0.0f));
    const ProbeField& field = ddgi.field();
    RaySet rays = makeRaySet(field.desc(), 11, 5);
    ProbeTrace trace;
    trace.work.assign(std::size_t(field.probeCount()), ProbeWork::Full);
    trace.work[3] = ProbeWork::FixedOnly;  // its blend hits are neither traced nor grouped
    const std::size_t hits = std::size_t(field.probeCount()) * std::size_t(rays.blendRays);
    HitCache whileTracing, afterwards;
    for (int repeat = 0; repeat < 2; ++repeat) {  // the second frame reuses the grown tables
        whileTracing.begin(hitCacheCellSize(field), hits);
        traceProbes(tracer, field, rays, trace, &whileTracing);
        whileTracing.finish();
        groupProbeHits(afterwards, field, rays, trace);
        ASSERT_EQ(whileTracing.groups(), afterwards.groups());
        EXPECT_GT(whileTracing.groups(), 100u);
        std::size_t grouped = 0;
        for (std::size_t h = 0; h < hits; ++h) {
            if (h / std::size_t(rays.blendRays) == 3) continue;
            std::uint32_t a = whileTracing.groupOf(h), b = afterwards.groupOf(h);
            ASSERT_EQ(a == HitCache::kNone, b == HitCache::kNone) << h;
            if (a == HitCache::kNone) continue;
            ++grouped;
            EXPECT_EQ(whileTracing.representative(a), afterwards.representative(b)) << h;
        }
        EXPECT_GT(grouped, hits / 4);  // the yard is open: many rays see the sky
        for (std::size_t g = 0; g < whileTracing.groups(); ++g)
            EXPECT_NE(whileTracing.representative(g) / std::size_t(rays.blendRays), 3u);
    }
}

TEST(DdgiHitCache, RefreshingCellsEveryOtherFrameKeepsTheConvergedField) {
    // hit_cache_refresh 2: a cell seen last frame re-uses last frame's values every other
    // frame. About half the groups are evaluated per frame, and the converged field matches
    // evaluating every group every frame.
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    auto run = [&](const char* refresh, std::int64_t* groups, std::int64_t* evaluated) {
        auto d = std::make_unique<DdgiSystem>(
            tracer, test::descFrom({{"probes", "6,3,6"}, {"spacing", "0.6"}, {"rays", "128"}, {"hysteresis", "0.8"},
                                    {"relocate", "false"}, {"classify", "false"}, {"hit_cache_refresh", refresh}}));
        for (int f = 0; f < 40; ++f) {
            DdgiFrameStats st = d->update(glm::vec3(0.0f));
            *groups = st.cacheGroups;
            *evaluated = st.cacheGroupsEvaluated;
        }
        return d;
    };
    std::int64_t groups1 = 0, evaluated1 = 0, groups2 = 0, evaluated2 = 0;
    auto every = run("1", &groups1, &evaluated1);
    auto other = run("2", &groups2, &evaluated2);
    EXPECT_EQ(evaluated1, groups1);
    EXPECT_GT(groups2, 100);
    EXPECT_GT(evaluated2, groups2 / 4);
    EXPECT_LT(evaluated2, groups2 * 3 / 4);
    const double difference = fieldDifference(every->field(), other->field());
    std::printf("hit_cache_refresh 2: %lld of %lld groups evaluated; converged field differs by %.3f %% (mean |diff|)\n",
                (long long)evaluated2, (long long)groups2, 100.0 * difference);
    EXPECT_LT(difference, 0.01);
}

TEST(DdgiHitCache, ChangedLightsReevaluateEveryCell) {
    // Re-used values saw last frame's lights: when a light moves or changes colour, the frame
    // after evaluates every group again (then alternates as before).
    Scene scene = test::openYard();
    ASSERT_FALSE(scene.lights.empty());
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, test::descFrom({{"probes", "6,3,6"}, {"spacing", "0.6"}, {"rays", "128"},
                                            {"relocate", "false"}, {"classify", "false"}, {"hit_cache_refresh", "2"}}));
    for (int f = 0; f < 4; ++f) ddgi.update(glm::vec3(0.0f));
    DdgiFrameStats steady = ddgi.update(glm::vec3(0.0f));
    EXPECT_LT(steady.cacheGroupsEvaluated, steady.cacheGroups * 3 / 4);
    scene.lights[0].emission *= 0.5f;
    DdgiFrameStats changed = ddgi.update(glm::vec3(0.0f));
    EXPECT_GT(changed.cacheGroups, 100);
    EXPECT_EQ(changed.cacheGroupsEvaluated, changed.cacheGroups);
    DdgiFrameStats after = ddgi.update(glm::vec3(0.0f));
    EXPECT_LT(after.cacheGroupsEvaluated, after.cacheGroups * 3 / 4);
    scene.lights[0].direction = glm::normalize(scene.lights[0].direction + glm::vec3(0.1f, 0.0f, 0.0f));
    scene.lights[0].position += glm::vec3(0.05f, 0.0f, 0.0f);
    DdgiFrameStats moved = ddgi.update(glm::vec3(0.0f));
    EXPECT_EQ(moved.cacheGroupsEvaluated, moved.cacheGroups);
}
