// The frame plan drives the frame: for scenes that need and do not need each pass, the stages
// the renderer's timers recorded are exactly the passes planFrame listed, for every method.
#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "gi/methods.h"
#include "render/frame/frame_renderer.h"
#include "scenes/primitives.h"
#include "support/test_support.h"

namespace voxgi {
namespace {

// A 2 m box (open at the front) seen from outside, with the lights and sky given.
Scene box(std::vector<Light> lights, bool sky, bool emitter) {
    Scene s;
    Material wall;
    wall.name = "wall";
    wall.albedo = glm::vec3(0.6f);
    s.materials.push_back(wall);
    s.meshes.push_back(makeBox(glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)), 0, true));
    if (emitter) {
        Material glow = wall;
        glow.name = "glow";
        glow.emission = glm::vec3(2.0f);
        s.materials.push_back(glow);
        s.meshes.push_back(makeBox(glm::scale(glm::mat4(1.0f), glm::vec3(0.2f)), 1, false));
    }
    s.lights = std::move(lights);
    s.sky.enabled = sky;
    s.sky.radiance = glm::vec3(0.3f);
    s.camera.eye = glm::vec3(0.0f, 0.2f, -0.6f);
    s.camera.target = glm::vec3(0.0f, 0.0f, 1.0f);
    s.camera.width = s.camera.height = 32;
    // Which passes run does not depend on sizes: small volumes, maps and ray counts keep these
    // tests to seconds on llvmpipe.
    for (const auto& [key, value] : {std::pair{"lpv.resolution", "8"}, {"lpv.rsm_size", "32"},
                                     {"lpv.sky_bounce_size", "32"}, {"lpv.gbuffer_blocker_size", "32"},
                                     {"ddgi.rays", "32"}, {"sky.resolution", "8"}})
        s.gi.set(key, value);
    return s;
}

Light pointLight() {
    Light l;
    l.type = LightType::Point;
    l.position = glm::vec3(0.2f, 0.6f, 0.3f);
    l.emission = glm::vec3(1.0f);
    return l;
}

Light sunAndSpot(LightType type) {
    Light l;
    l.type = type;
    l.position = glm::vec3(0.0f, 0.8f, 0.0f);
    l.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
    l.emission = glm::vec3(2.0f);
    return l;
}

std::set<std::string> recorded(FrameRenderer& r) {
    std::set<std::string> stages;
    for (const auto& [stage, samples] : r.timers().samples()) stages.insert(stage);
    return stages;
}

std::set<std::string> planned(const FramePlan& plan) {
    std::set<std::string> passes;
    for (const PlannedPass& p : plan.passes) passes.insert(p.name);
    return passes;
}

void expectPlanRuns(const Scene& scene, const std::string& method, const std::string& what) {
    FramePlan plan = planFrame(scene, method, 2);
    FrameRenderer renderer(scene, FrameOptions{}, plan);
    renderer.renderFrame();
    renderer.renderFrame();
    EXPECT_EQ(recorded(renderer), planned(plan)) << method << " on " << what << "\n" << plan.describe();
    for (const PlannedPass& p : plan.skipped) EXPECT_FALSE(plan.runs(p.name)) << p.name << " both run and skipped";
}

class FramePlanTest : public ::testing::Test {
protected:
    void SetUp() override { test::useHeadlessContext(); }
};

TEST_F(FramePlanTest, FramePassesFollowTheScene) {
    struct Case {
        const char* what;
        Scene scene;
        std::set<std::string> passes;
    };
    const Case cases[] = {
        {"a point light", box({pointLight()}, false, false), {"gbuffer", "shadow_cube", "direct_light"}},
        {"a sun and a spot", box({sunAndSpot(LightType::Directional), sunAndSpot(LightType::Spot)}, false, false),
         {"gbuffer", "shadow_map", "shadow_sun", "direct_light"}},
        {"a sun", box({sunAndSpot(LightType::Directional)}, false, false), {"gbuffer", "shadow_sun", "direct_light"}},
        {"sky and an emitter, no lights", box({}, true, true), {"gbuffer", "sky_volume", "sky_light", "emission_sky"}},
        {"nothing but a sky", [] {
             Scene s = box({}, true, false);
             s.meshes.clear();
             return s;
         }(),
         {"emission_sky"}},
    };
    for (const Case& c : cases) {
        EXPECT_EQ(planned(planFrame(c.scene, "direct", 1)), c.passes) << c.what;
        expectPlanRuns(c.scene, "direct", c.what);
    }
    // What no scene has is not listed at all.
    FramePlan plan = planFrame(test::cornellBox(), "direct", 1);
    for (const char* absent : {"sky_volume", "reflections", "accumulate"}) {
        EXPECT_FALSE(plan.runs(absent));
        for (const PlannedPass& p : plan.skipped) EXPECT_NE(p.name, absent);
    }
}

TEST_F(FramePlanTest, EveryMethodRunsItsPlan) {
    Scene lit = box({pointLight()}, false, false);
    Scene dark = box({}, true, true);
    for (const std::string& method : builtMethods()) {
        expectPlanRuns(lit, method, "a lit box");
        expectPlanRuns(dark, method, "a box without lights");
    }
    // Settings that add or remove passes.
    Scene gl = lit;
    gl.gi.set("lpv.backend", "gl");
    expectPlanRuns(gl, "clpv", "the gl back end");
    EXPECT_TRUE(planFrame(gl, "clpv", 1).runs("lpv.static_blockers"));
    EXPECT_FALSE(planFrame(gl, "clpv", 1).runs("lpv.upload"));
    Scene noCamera = lit;
    noCamera.gi.set("lpv.gbuffer_blocker_size", "0");
    EXPECT_FALSE(planFrame(noCamera, "lpv", 1).runs("lpv.gbuffer_readback"));
    expectPlanRuns(noCamera, "lpv", "no G-buffer blockers");
    EXPECT_TRUE(planFrame(dark, "lpv", 1).runs("lpv.sky_bounce")) << "no lights, a sky: its bounce is the light";
    EXPECT_FALSE(planFrame(dark, "lpv", 1).runs("lpv.rsm"));
    const Scene pitch = box({}, false, true);
    EXPECT_FALSE(planFrame(pitch, "lpv", 1).runs("lpv.propagate")) << "no lights, no sky: nothing to propagate";
    Scene ambient = lit;
    EXPECT_FALSE(planFrame(ambient, "ambient", 1).runs("ambient.apply"));
    ambient.gi.set("ambient.irradiance", "0.5");
    EXPECT_TRUE(planFrame(ambient, "ambient", 1).runs("ambient.apply"));
    expectPlanRuns(ambient, "ambient", "an ambient irradiance");
}

// Static work persists: the voxelized-scene blockers of a cascade are made once while it stays
// put, though every update (lpv.reuse off) redoes the dynamic blockers, on both back ends.
TEST_F(FramePlanTest, StaticBlockersAreMadeOncePerPlacement) {
    // SH: the voxelized blockers once, the surfels' blockers every update. Ordinates: the
    // voxelized surfaces once, and no blockers pass.
    for (const char* transport : {"sh", "ordinates"})
        for (const char* backend : {"cpu", "gl"}) {
            SCOPED_TRACE(std::string(transport) + " " + backend);
            Scene lit = box({pointLight()}, false, false);
            lit.gi.set("lpv.reuse", "false");
            lit.gi.set("lpv.backend", backend);
            lit.gi.set("lpv.transport", transport);
            FramePlan plan = planFrame(lit, "clpv", 1);
            ASSERT_TRUE(plan.runs("lpv.static_blockers"));
            FrameRenderer renderer(lit, FrameOptions{}, plan);
            for (int frame = 0; frame < 3; ++frame) renderer.renderFrame();
            const auto& samples = renderer.timers().samples();
            ASSERT_TRUE(samples.count("lpv.static_blockers"));
            EXPECT_EQ(samples.at("lpv.static_blockers").cpuMs.size(), 1u);
            ASSERT_TRUE(samples.count("lpv.propagate"));
            const auto& propagate = samples.at("lpv.propagate");
            EXPECT_EQ(std::max(propagate.cpuMs.size(), propagate.gpuMs.size()), 3u);
            if (std::string(transport) == "ordinates") {
                EXPECT_FALSE(plan.runs("lpv.blockers"));
                continue;
            }
            const auto& blockers = samples.at("lpv.blockers");
            EXPECT_EQ(std::max(blockers.cpuMs.size(), blockers.gpuMs.size()), 3u);
        }
}

}  // namespace
}  // namespace voxgi
