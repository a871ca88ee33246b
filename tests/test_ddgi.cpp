// DDGI on the CPU: furnace convergence, leaks through a thin wall, extreme settings, scrolling
// against a freshly built volume, determinism, and the settings reader.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gi/ddgi/ddgi_system.h"
#include "gi/ddgi/occupancy_query.h"
#include "gi/ddgi/probe_blend.h"
#include "gi/ddgi/probe_sampling.h"
#include "gi/octahedral/octahedral.h"
#include "gi/raytrace/ray_tracer.h"
#include "scenes/errors.h"
#include "shaders/shared/constants.h"
#include "test_ddgi_scenes.h"

using namespace voxgi;

namespace {

using test::descFrom;

using shading::kPi;

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool atlasFinite(const ProbeField& f) {
    for (const glm::vec4& t : f.irradiance.texels)
        if (!finite(glm::vec3(t))) return false;
    for (const glm::vec4& t : f.distance.texels)
        if (!std::isfinite(t.x) || !std::isfinite(t.y)) return false;
    return true;
}

void runFrames(DdgiSystem& s, int frames, glm::vec3 eye = glm::vec3(0.0f)) {
    for (int i = 0; i < frames; ++i) s.update(eye);
}

// Irradiance on the six inner walls of a furnace box (points a quarter in from the centre).
void checkFurnace(float rho, const std::string& probes, const std::string& hitCache = "off") {
    const float le = 1.0f;
    Scene scene = test::furnaceBox(rho, le);
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, descFrom({{"probes", probes}, {"rays", "64"}, {"hysteresis", "0"}, {"hit_cache", hitCache}}));
    runFrames(ddgi, 60);
    const float expected = kPi * le / (1.0f - rho);
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        glm::vec3 p = -n * 0.999f + glm::vec3(0.13f, -0.21f, 0.17f) * (glm::vec3(1.0f) - glm::abs(n));
        glm::vec3 e = sampleIrradiance(ddgi.field(), p, n, n);
        EXPECT_NEAR(e.x, expected, 0.05f * expected) << "rho " << rho << " normal " << n.x << n.y << n.z;
        EXPECT_NEAR(e.y, e.x, 1e-3f * expected);
    }
    for (int p = 0; p < ddgi.field().probeCount(); ++p)
        EXPECT_NEAR(ddgi.field().meanIrradiance(p).x, expected, 0.05f * expected);
}

}  // namespace

TEST(Ddgi, FurnaceConvergesToAnalyticIrradiance) {
    checkFurnace(0.5f, "2");
    checkFurnace(0.9f, "2");
}

TEST(Ddgi, SingleProbeFurnace) { checkFurnace(0.5f, "1"); }

TEST(Ddgi, FurnaceConvergesWithTheHitCache) {
    for (const char* mode : {"probes", "all"}) {
        checkFurnace(0.5f, "2", mode);
        checkFurnace(0.9f, "2", mode);
    }
}

// Mean irradiance over floor points of each room (normal up).
struct RoomLight {
    float lit = 0, dark = 0;
};

RoomLight measureRooms(bool classify, bool relocate, const std::string& probes, const std::string& hitCache = "off") {
    Scene scene = test::twoRooms();
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, descFrom({{"probes", probes},
                                      {"rays", "128"},
                                      {"hysteresis", "0.5"},
                                      {"hit_cache", hitCache},
                                      {"classify", classify ? "true" : "false"},
                                      {"relocate", relocate ? "true" : "false"}}));
    runFrames(ddgi, 24);
    RoomLight r;
    int n = 0;
    for (float x = 0.05f; x < 1.95f; x += 0.1f)
        for (float z = -0.45f; z < 0.46f; z += 0.15f) {
            r.lit += sampleIrradiance(ddgi.field(), glm::vec3(-x, -0.5f, z), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)).x;
            r.dark += sampleIrradiance(ddgi.field(), glm::vec3(x, -0.5f, z), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)).x;
            ++n;
        }
    r.lit /= float(n);
    r.dark /= float(n);
    return r;
}

TEST(Ddgi, ThinWallLeakStaysUnderTwoPercent) {
    // 8 probes along x: the wall lies between two probe planes; 7: a probe plane inside the wall.
    for (const char* probes : {"8,3,3", "7,3,3"}) {
        RoomLight on = measureRooms(true, true, probes);
        RoomLight off = measureRooms(false, false, probes);
        std::printf("probes %s: leak with classification+relocation dark/lit = %.3e (lit %.4g W/m^2), without %.3e\n",
                    probes, on.dark / on.lit, on.lit, off.dark / off.lit);
        ASSERT_GT(on.lit, 0.0f);
        EXPECT_LT(on.dark, 0.02f * on.lit) << probes;
        // Hits on the two faces of the wall have opposite normals: the hit cache never shares
        // light across it.
        RoomLight cached = measureRooms(true, true, probes, "all");
        std::printf("probes %s: leak with the hit cache (all) %.3e\n", probes, cached.dark / cached.lit);
        ASSERT_GT(cached.lit, 0.0f);
        EXPECT_LT(cached.dark, 0.02f * cached.lit) << probes;
    }
}

TEST(Ddgi, ChebyshevHandlesZeroVarianceAndNearPoints) {
    EXPECT_EQ(chebyshevVisibility(1.0f, 2.0f, 4.0f), 1.0f);   // r < mean
    EXPECT_EQ(chebyshevVisibility(2.0f, 2.0f, 4.0f), 1.0f);   // r == mean, zero variance
    EXPECT_EQ(chebyshevVisibility(2.5f, 2.0f, 4.0f), 0.0f);   // r > mean, zero variance
    EXPECT_EQ(chebyshevVisibility(2.5f, 2.0f, 3.9f), 0.0f);   // negative variance from filtering
    float p = chebyshevVisibility(3.0f, 2.0f, 5.0f);          // variance 1, distance 1: (1/2)^3
    EXPECT_NEAR(p, 0.125f, 1e-6f);
}

TEST(Ddgi, HysteresisOneFreezesAfterTheFirstBlend) {
    Scene scene = test::furnaceBox(0.5f, 1.0f);
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, descFrom({{"probes", "2"}, {"rays", "32"}, {"hysteresis", "1"}}));
    runFrames(ddgi, 1);
    std::vector<glm::vec4> first = ddgi.field().irradiance.texels;
    runFrames(ddgi, 4);
    EXPECT_TRUE(atlasFinite(ddgi.field()));
    EXPECT_EQ(first, ddgi.field().irradiance.texels);
    // One frame from an empty field: just the emission, E = pi * le.
    EXPECT_NEAR(ddgi.field().meanIrradiance(0).x, kPi, 1e-3f);
}

TEST(Ddgi, HysteresisZeroIsFiniteAndFollowsTheNewValue) {
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, descFrom({{"probes", "4,2,4"}, {"rays", "32"}, {"hysteresis", "0"}}));
    runFrames(ddgi, 6);
    EXPECT_TRUE(atlasFinite(ddgi.field()));
    glm::vec3 e = sampleIrradiance(ddgi.field(), glm::vec3(2.0f, 0.0f, 2.0f), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0));
    EXPECT_TRUE(finite(e));
    EXPECT_GT(e.x, 0.0f);  // the sky and the lit blocks
}

TEST(Ddgi, ProbeExactlyOnASurface) {
    // A flat floor: the bounds are flat, so the single probe sits exactly on the surface.
    Scene scene;
    scene.materials.push_back(Material{});
    scene.meshes.push_back(makeQuad({glm::vec3(-1, 0, 1), glm::vec3(1, 0, 1), glm::vec3(1, 0, -1), glm::vec3(-1, 0, -1)}, 0));
    Light sun;
    sun.type = LightType::Directional;
    sun.emission = glm::vec3(3.0f);
    scene.lights.push_back(sun);
    scene.sky.enabled = true;
    scene.sky.radiance = glm::vec3(0.5f);
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, descFrom({{"probes", "1"}, {"spacing", "0.5"}, {"rays", "64"}}));
    ASSERT_FLOAT_EQ(ddgi.field().probePosition(0).y, 0.0f);
    runFrames(ddgi, 8);
    EXPECT_TRUE(atlasFinite(ddgi.field()));
    glm::vec3 e = sampleIrradiance(ddgi.field(), glm::vec3(0.3f, 0.0f, 0.2f), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0));
    EXPECT_TRUE(finite(e));
    // Upward: the sky's pi * L at most (the floor hides nothing above it).
    EXPECT_GE(e.x, 0.0f);
    EXPECT_LE(e.x, kPi * 0.5f * 1.05f);
}

TEST(Ddgi, AllProbesInsideGeometryAreOffAndGiveZero) {
    Scene scene;
    scene.materials.push_back(Material{});
    scene.meshes.push_back(makeBox(glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)), 0, false));  // solid
    Light l;
    l.position = glm::vec3(0.0f, 3.0f, 0.0f);
    scene.lights.push_back(l);
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, descFrom({{"probes", "3"}, {"rays", "32"}, {"relocate", "false"}}));
    runFrames(ddgi, 3);
    ProbeStateCounts c = countStates(ddgi.field());
    EXPECT_EQ(c.off, ddgi.field().probeCount());
    EXPECT_TRUE(atlasFinite(ddgi.field()));
    glm::vec3 e = sampleIrradiance(ddgi.field(), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0));
    EXPECT_EQ(e, glm::vec3(0.0f));
}

TEST(Ddgi, GeometryQueryTurnsProbesOffAndToSleep) {
    Scene scene = test::furnaceBox(0.5f, 1.0f, 4.0f);
    RayTracer tracer(scene);
    GeometryQuery q;
    q.insideSolid = [](glm::vec3 p) { return p.x > 0.0f; };
    DdgiSystem ddgi(tracer, descFrom({{"probes", "4"}, {"rays", "32"}, {"relocate", "false"}}), q);
    runFrames(ddgi, 2);
    ProbeStateCounts c = countStates(ddgi.field());
    EXPECT_EQ(c.off, 32);
    // The box is 4 m with 1 m cells: the 8 inner probes see no wall within a cell and sleep.
    EXPECT_EQ(c.sleeping, 4);
    EXPECT_EQ(c.active, 28);
}

TEST(Ddgi, RelocationMovesProbesOutOfAThinWall) {
    Scene scene = test::twoRooms(0.1f);
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, descFrom({{"probes", "7,3,3"}, {"rays", "64"}}));
    runFrames(ddgi, 3);
    for (int p = 0; p < ddgi.field().probeCount(); ++p) {
        glm::vec3 offset = ddgi.field().probes[std::size_t(p)].offset;
        const ProbeVolume& v = ddgi.field().volumes()[0];
        EXPECT_TRUE(glm::all(glm::lessThanEqual(glm::abs(offset), 0.45f * v.spacing + 1e-6f)));
        glm::vec3 pos = ddgi.field().probePosition(p);
        if (ddgi.field().probes[std::size_t(p)].state != ProbeState::Off) {
            EXPECT_GT(std::abs(pos.x), 0.05f) << p;
        }
    }
}

namespace {
// Per-probe mean irradiance keyed by rounded world position.
std::map<std::tuple<int, int, int>, glm::vec3> probeValues(const ProbeField& f) {
    std::map<std::tuple<int, int, int>, glm::vec3> out;
    for (int p = 0; p < f.probeCount(); ++p) {
        glm::vec3 w = f.probePosition(p) * 1000.0f;
        out[{int(std::lround(w.x)), int(std::lround(w.y)), int(std::lround(w.z))}] = f.meanIrradiance(p);
    }
    return out;
}
}  // namespace

TEST(Ddgi, ScrollingMatchesAFreshVolume) {
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    const std::map<std::string, std::string> keys = {{"probes", "4,3,4"}, {"spacing", "0.5"}, {"rays", "64"},
                                                     {"hysteresis", "0.5"}, {"scroll", "true"}, {"energy", "0"},
                                                     {"irradiance_threshold", "1e20"}, {"brightness_threshold", "1e20"},
                                                     {"classify", "false"}, {"relocate", "false"}};
    const glm::vec3 start(0.1f, 1.0f, -0.2f);
    const glm::vec3 moves[3] = {{0.5f, 0, 0}, {0, -0.5f, 0}, {0, 0, 0.5f}};
    // With the hit cache sharing light visibility too: the groups depend on the hits alone.
    for (const glm::vec3& move : moves) {
      for (const char* cache : {"off", "all"}) {
        auto cachedKeys = keys;
        cachedKeys["hit_cache"] = cache;
        DdgiSystem moving(tracer, descFrom(cachedKeys));
        runFrames(moving, 10, start);
        runFrames(moving, 30, start + move);
        Scene moved = scene;
        moved.camera.eye = start + move;
        RayTracer movedTracer(moved);
        DdgiSystem fresh(movedTracer, descFrom(cachedKeys));
        runFrames(fresh, 40, start + move);
        auto a = probeValues(moving.field()), b = probeValues(fresh.field());
        ASSERT_EQ(a.size(), b.size());
        for (const auto& [key, value] : a) {
            auto it = b.find(key);
            ASSERT_NE(it, b.end()) << "probe position differs after scrolling";
            EXPECT_NEAR(value.x, it->second.x, 1e-3f * (1.0f + it->second.x));
            EXPECT_NEAR(value.z, it->second.z, 1e-3f * (1.0f + it->second.z)) << cache;
        }
      }
    }
}

TEST(Ddgi, DeterministicForAFixedSeed) {
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    for (const char* cache : {"off", "all"}) {
        auto run = [&](const std::string& seed) {
            DdgiSystem ddgi(tracer, descFrom({{"probes", "4,2,4"}, {"rays", "32"}, {"seed", seed}, {"hit_cache", cache}}));
            runFrames(ddgi, 3);
            return ddgi.field().irradiance.texels;
        };
        EXPECT_EQ(run("7"), run("7")) << cache;
        EXPECT_NE(run("7"), run("8")) << cache;
    }
}

TEST(Ddgi, SettingsReaderRejectsTyposAndBadValues) {
    EXPECT_THROW(descFrom({{"ray", "64"}}), InputError);
    EXPECT_THROW(descFrom({{"rays", "0"}}), InputError);
    EXPECT_THROW(descFrom({{"hysteresis", "1.5"}}), InputError);
    EXPECT_THROW(descFrom({{"probes", "4,4"}}), InputError);
    EXPECT_THROW(descFrom({{"direct", "maps"}}), InputError);
    EXPECT_THROW(descFrom({{"hit_cache", "yes"}}), InputError);
    EXPECT_THROW(descFrom({{"hit_cache_cells", "0"}}), InputError);
    EXPECT_THROW(descFrom({{"probes", "100"}}), InputError);                   // memory
    EXPECT_THROW(descFrom({{"probes", "64"}, {"rays", "1024"}}), InputError);  // 268M rays
    DdgiDesc d = descFrom({{"probes", "16,8,12"}, {"spacing", "1"}});
    EXPECT_EQ(d.probeCounts, glm::ivec3(16, 8, 12));
    EXPECT_EQ(d.rays, 256);
    EXPECT_EQ(d.raysPerProbe(), 288);
    EXPECT_FLOAT_EQ(d.hysteresis, 0.97f);
    EXPECT_EQ(d.hitCache, DdgiHitCache::All);
    EXPECT_EQ(descFrom({{"hit_cache", "off"}}).hitCache, DdgiHitCache::Off);
}

TEST(Ddgi, OcclusionProbesReconstructShadowsLikeShadowRays) {
    // The yard: the blocks cast shadows on the floor. With light visibility reconstructed from
    // occlusion probes, the probes' irradiance stays close to the shadow-ray result.
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    // Every hit tests its own lights (no hit cache): the shadow-ray count is the comparison.
    const std::map<std::string, std::string> base = {{"probes", "6,3,6"}, {"spacing", "0.6"}, {"rays", "128"},
                                                     {"hysteresis", "0.8"}, {"relocate", "false"},
                                                     {"hit_cache", "off"}};
    auto withMode = [&](const std::string& mode) {
        auto keys = base;
        keys["direct"] = mode;
        return descFrom(keys);
    };
    DdgiSystem rays(tracer, withMode("rays")), occlusion(tracer, withMode("occlusion"));
    std::int64_t rayShadows = 0, occlusionShadows = 0;
    for (int f = 0; f < 40; ++f) {
        rayShadows += rays.update(glm::vec3(0.0f)).shadowQueries;
        occlusionShadows += occlusion.update(glm::vec3(0.0f)).shadowQueries;
    }
    ASSERT_FALSE(occlusion.field().occlusion.texels.empty());
    EXPECT_TRUE(rays.field().occlusion.texels.empty());
    // Visibility in [0, 1], some of it shadowed (the blocks), most of it lit.
    int shadowed = 0, total = 0;
    for (const glm::vec4& t : occlusion.field().occlusion.texels) {
        ASSERT_GE(t.x, 0.0f);
        ASSERT_LE(t.x, 1.0f);
        shadowed += t.x < 0.5f;
        ++total;
    }
    EXPECT_GT(shadowed, 0);
    EXPECT_LT(shadowed, total);
    EXPECT_LT(occlusionShadows * 3, rayShadows);  // a quarter of the hits (stride 4)
    double sumRays = 0.0, sumOcclusion = 0.0, sumDiff = 0.0;
    for (int p = 0; p < rays.field().probeCount(); ++p) {
        float a = rays.field().meanIrradiance(p).x, b = occlusion.field().meanIrradiance(p).x;
        sumRays += a;
        sumOcclusion += b;
        sumDiff += std::abs(a - b);
    }
    std::printf("occlusion probes vs shadow rays: mean probe irradiance %.4g vs %.4g, mean |difference| %.1f %%, "
                "shadow rays %lld vs %lld\n",
                sumOcclusion, sumRays, 100.0 * sumDiff / sumRays, (long long)occlusionShadows, (long long)rayShadows);
    EXPECT_NEAR(sumOcclusion, sumRays, 0.1 * sumRays);
    EXPECT_LT(sumDiff, 0.2 * sumRays);
}

TEST(Ddgi, VoxelOccupancyPutsProbesFarFromGeometryToSleep) {
    // A 4 m closed box with 1 m cells: the 8 inner probes are 1.5 m from every wall.
    Scene scene = test::furnaceBox(0.5f, 1.0f, 4.0f);
    RayTracer tracer(scene);
    DdgiDesc desc = descFrom({{"probes", "4"}, {"rays", "32"}, {"relocate", "false"}});
    ProbeVolume volume = layoutVolumes(desc, scene.bounds(), scene.camera.eye).front();
    auto voxels = voxelizeForProbes(scene, volume);
    GeometryQuery query = occupancyQuery(voxels, volume);
    ASSERT_TRUE(query.distanceToGeometry);
    EXPECT_EQ(query.distanceToGeometry(glm::vec3(1.5f, 1.5f, 1.5f)), 0.0f);  // next to three walls
    EXPECT_GT(query.distanceToGeometry(glm::vec3(0.5f, 0.5f, 0.5f)), 1.0f);   // the inner probes
    DdgiSystem ddgi(tracer, desc, query);
    runFrames(ddgi, 2);
    ProbeStateCounts c = countStates(ddgi.field());
    EXPECT_EQ(c.sleeping, 8);
    EXPECT_EQ(c.active, 56);
    EXPECT_EQ(c.off, 0);
    // With the occupancy known, a sleeping probe traces nothing between its full updates (one
    // every sleep_interval frames): over 10 frames the 56 active probes trace 10 x 64 rays, the
    // 8 sleepers 64 once each (with rays alone they also trace the 32 fixed rays every frame).
    std::int64_t rays = 0;
    for (int f = 0; f < desc.sleepInterval; ++f) rays += ddgi.update(scene.camera.eye).raysTraced;
    EXPECT_EQ(rays, std::int64_t(desc.sleepInterval) * 56 * 64 + 8 * 64);
    c = countStates(ddgi.field());
    EXPECT_EQ(c.sleeping, 8);
    EXPECT_EQ(c.active, 56);
}

TEST(Ddgi, ScrollingVolumesCentreAheadOfTheCameraInsideTheScene) {
    Bounds box;
    box.min = glm::vec3(0.0f);
    box.max = glm::vec3(4.0f);
    ProbeVolume v;
    v.counts = glm::ivec3(4);
    v.spacing = glm::vec3(0.5f);  // 1.5 m from the first probe to the last
    // Inside: a quarter of the extent ahead along the view.
    glm::vec3 c = scrollCentre(v, glm::vec3(2.0f), glm::vec3(1, 0, 0), 0.25f, box);
    EXPECT_NEAR(c.x, 2.375f, 1e-6f);
    EXPECT_NEAR(c.y, 2.0f, 1e-6f);
    // A camera 3 m outside the box looking in: slid back inside, touching the near wall.
    c = scrollCentre(v, glm::vec3(2.0f, 2.0f, -3.0f), glm::vec3(0, 0, 1), 0.25f, box);
    EXPECT_NEAR(c.z, 0.75f, 1e-6f);
    // A volume wider than the box sits on the box's centre along that axis.
    v.spacing = glm::vec3(2.0f);
    c = scrollCentre(v, glm::vec3(2.0f, 2.0f, -3.0f), glm::vec3(0, 0, 1), 0.25f, box);
    EXPECT_NEAR(c.z, 2.0f, 1e-6f);

    // End to end: two cascades seen from outside the box (the Cornell box's camera) light the
    // walls instead of sitting in the empty space in front of it.
    Scene scene = test::furnaceBox(0.5f, 1.0f, 4.0f);
    scene.camera.eye = glm::vec3(0.0f, 0.0f, -5.0f);
    scene.camera.target = glm::vec3(0.0f);
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, descFrom({{"probes", "4"}, {"spacing", "0.5"}, {"rays", "64"}, {"cascades", "2"}}));
    for (int i = 0; i < 4; ++i) ddgi.update(scene.camera.eye, nullptr, glm::vec3(0, 0, 1));
    const ProbeVolume& finest = ddgi.field().volumes().front();
    const Bounds bounds = scene.bounds();
    for (int z = 0; z < finest.counts.z; ++z) {
        const glm::vec3 p = finest.basePosition(glm::ivec3(0, 0, z));
        EXPECT_GE(p.z, bounds.min.z);
        EXPECT_LE(p.z, bounds.max.z);
    }
    ProbeSampler sampler(ddgi.field());
    const glm::vec3 floor(0.0f, bounds.min.y + 0.25f, bounds.min.z + 0.5f);
    EXPECT_GT(sampler.irradiance(floor, glm::vec3(0, 1, 0), glm::vec3(0, 0, -1)).x, 0.1f);
}

TEST(Ddgi, FieldChangeFallsAsTheFurnaceConverges) {
    Scene scene = test::furnaceBox(0.5f, 1.0f);
    RayTracer tracer(scene);
    DdgiSystem untracked(tracer, descFrom({{"probes", "2"}, {"rays", "64"}}));
    runFrames(untracked, DdgiSystem::kChangeWindow + 2);
    EXPECT_LT(untracked.fieldChange(), 0.0);  // off unless asked

    DdgiSystem ddgi(tracer, descFrom({{"probes", "2"}, {"rays", "64"}}));
    ddgi.trackChange();
    runFrames(ddgi, DdgiSystem::kChangeWindow);
    EXPECT_LT(ddgi.fieldChange(), 0.0);  // the window has not filled
    runFrames(ddgi, 1);
    const double early = ddgi.fieldChange();
    EXPECT_GT(early, 0.05);  // the bounces are still adding light
    runFrames(ddgi, 150);
    EXPECT_LT(ddgi.fieldChange(), 0.01);
    EXPECT_LT(ddgi.fieldChange(), 0.2 * early);
}

TEST(Ddgi, FittedGridsHaveCubicCellsAlongTheScenesShape) {
    Bounds b;
    b.min = glm::vec3(-4.0f, 0.0f, -2.0f);
    b.max = glm::vec3(4.0f, 2.0f, 2.0f);  // 8 x 2 x 4 m
    for (int cells : {4, 8}) {
        const ProbeVolume v = layoutVolumes(descFrom({{"fit_cells", std::to_string(cells)}}), b, glm::vec3(0.0f)).front();
        const float cell = 8.0f / float(cells);
        EXPECT_EQ(v.counts, glm::ivec3(cells, cells / 4, cells / 2)) << cells;
        EXPECT_NEAR(v.spacing.x, cell, 1e-6f);
        EXPECT_NEAR(v.spacing.y, cell, 1e-6f);
        EXPECT_NEAR(v.spacing.z, cell, 1e-6f);
        // Probes at cell centres: half a cell inside the bounds.
        EXPECT_NEAR(v.origin.x, b.min.x + 0.5f * cell, 1e-5f);
        EXPECT_NEAR(v.origin.y, b.min.y + 0.5f * cell, 1e-5f);
    }
    // The affordability check sees the fitted grid's worst case before anything is allocated.
    EXPECT_THROW(descFrom({{"fit_cells", "32"}, {"rays", "4096"}}), InputError);
}

TEST(Ddgi, CpuBlendMatchesAPlainSumOverEveryRay) {
    // The CPU blend sums from per-frame weight tables and leaves out (ray, texel) pairs whose
    // distance weight is below 1e-7 / rays of the texel's largest: against a plain double sum
    // over every ray, both atlases agree to 1e-5 relative, for the default exponent (repeated
    // squaring) and a fractional one (pow).
    Scene scene = test::furnaceBox(0.5f, 1.0f);
    for (const char* exponent : {"50", "7.5"}) {
        const DdgiDesc desc = descFrom({{"probes", "2"}, {"rays", "256"}, {"hysteresis", "0"},
                                        {"distance_exponent", exponent}});
        ProbeField field(desc, layoutVolumes(desc, scene.bounds(), glm::vec3(0.0f)));
        const RaySet rays = makeRaySet(desc, 1, 3);
        std::vector<int> probes(std::size_t(field.probeCount()));
        for (int p = 0; p < field.probeCount(); ++p) probes[std::size_t(p)] = p;
        const std::vector<BlendJob> jobs = makeBlendJobs(field, probes, rays.blendRays);
        ShadedRays shaded;
        shaded.raysPerJob = rays.blendRays;
        std::uint32_t state = 12345u;
        auto uniform = [&state] {
            state = state * 1664525u + 1013904223u;
            return float(state >> 8) / float(1u << 24);
        };
        for (std::size_t i = 0; i < jobs.size() * std::size_t(rays.blendRays); ++i)
            shaded.values.push_back(glm::vec4(2.0f * uniform(), uniform(), 3.0f * uniform(), 4.0f * uniform() - 1.0f));
        CpuBlend().blend(field, rays, shaded, jobs);

        const float e = std::stof(exponent);
        double worst = 0.0;
        for (const BlendJob& job : jobs) {
            const glm::vec4* v = &shaded.values[std::size_t(job.rayBase)];
            for (int y = 0; y < desc.irradianceTexels; ++y)
                for (int x = 0; x < desc.irradianceTexels; ++x) {
                    const glm::dvec3 dir(oct::texelDirection(x, y, desc.irradianceTexels));
                    glm::dvec3 sum(0.0);
                    double wsum = 0.0;
                    for (int k = 0; k < rays.blendRays; ++k) {
                        if (v[k].w < 0.0f) continue;
                        const double w = std::max(0.0, glm::dot(dir, glm::dvec3(rays.blendDirection(k))));
                        sum += w * glm::dvec3(v[k]), wsum += w;
                    }
                    const glm::dvec3 want = glm::pow(double(kPi) * sum / wsum, glm::dvec3(1.0 / desc.irradianceGamma));
                    const glm::vec4 got = field.irradiance.at(job.irradianceX + 1 + x, job.irradianceY + 1 + y);
                    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] - want[c]) / want[c]);
                }
            for (int y = 0; y < desc.distanceTexels; ++y)
                for (int x = 0; x < desc.distanceTexels; ++x) {
                    const glm::dvec3 dir(oct::texelDirection(x, y, desc.distanceTexels));
                    glm::dvec2 sum(0.0);
                    double wsum = 0.0;
                    for (int k = 0; k < rays.blendRays; ++k) {
                        const double w = std::pow(std::max(0.0, glm::dot(dir, glm::dvec3(rays.blendDirection(k)))), double(e));
                        const double d = std::min(double(v[k].w >= 0.0f ? v[k].w : -kBackfaceDistanceScale * v[k].w),
                                                  double(job.maxDistance));
                        sum += w * glm::dvec2(d, d * d), wsum += w;
                    }
                    const glm::dvec2 want = sum / wsum;
                    const glm::vec4 got = field.distance.at(job.distanceX + 1 + x, job.distanceY + 1 + y);
                    for (int c = 0; c < 2; ++c) worst = std::max(worst, std::abs(got[c] - want[c]) / want[c]);
                }
        }
        std::printf("distance exponent %s: CPU blend against a plain double sum, max relative difference %.2e\n",
                    exponent, worst);
        EXPECT_LT(worst, 1e-5) << exponent;
    }
}

TEST(Ddgi, FittedGridsScaleWithTheScene) {
    // The grid of a scene scaled by k is k times the grid: no absolute floor on the extent
    // (the stability suite's 0.1 mm Cornell box had lost 9 % of its light).
    for (const float k : {1e-4f, 1e4f}) {
        Bounds unit, scaled;
        unit.min = glm::vec3(0.0f), unit.max = glm::vec3(0.55f, 0.55f, 0.0f);  // flat along z
        scaled.min = unit.min * k, scaled.max = unit.max * k;
        const DdgiDesc desc = descFrom({});
        const ProbeVolume a = layoutVolumes(desc, unit, glm::vec3(0.0f)).front();
        const ProbeVolume b = layoutVolumes(desc, scaled, glm::vec3(0.0f)).front();
        EXPECT_EQ(a.counts, b.counts) << k;
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(b.spacing[c], k * a.spacing[c], 1e-5f * k * a.spacing[c]) << k;
            EXPECT_NEAR(b.origin[c], k * a.origin[c], 1e-5f * k * (std::abs(a.origin[c]) + a.spacing[c])) << k;
        }
    }
}
