// Many-view evaluation: views drawn in a scene's free space (render/view/view_sampler.h), their
// file round trip, the summaries across views (tools/eval_views.h), and `voxgi eval --views`.
#include <cmath>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gi/raytrace/ray_tracer.h"
#include "render/view/view_sampler.h"
#include "scenes/errors.h"
#include "scenes/primitives.h"
#include "support/test_support.h"
#include "tools/eval_views.h"
#include "volumes/geometry_volume.h"

using namespace voxgi;
using namespace voxgi::test;

namespace {

// A closed room [0, 4]^3 (faces inward) with a solid block [1.4, 2.6]^3 in its middle.
Scene roomWithBlock() {
    Scene scene;
    scene.materials = {Material{}};
    scene.meshes.push_back(makeBox(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(2.0f)), glm::vec3(4.0f)), 0, true));
    scene.meshes.push_back(makeBox(glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(2.0f)), glm::vec3(1.2f)), 0));
    scene.camera.eye = glm::vec3(0.5f, 2.0f, 0.5f);
    scene.camera.target = glm::vec3(2.0f);
    scene.camera.width = scene.camera.height = 32;
    return scene;
}

bool insideBlock(glm::vec3 p) { return glm::all(glm::greaterThan(p, glm::vec3(1.4f))) && glm::all(glm::lessThan(p, glm::vec3(2.6f))); }

nlohmann::json readJson(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

}  // namespace

TEST(ViewSampler, ViewsStandInFreeSpaceAndSeeTheirTargets) {
    const Scene scene = roomWithBlock();
    view::ViewSampling sampling;
    sampling.count = 24;
    sampling.seed = 7;
    const std::vector<Camera> views = view::sampleViews(scene, sampling);
    ASSERT_EQ(views.size(), 24u);
    VoxelizeSettings settings;
    settings.voxelSize = 4.0f / float(sampling.voxelsAcross);
    const SparseGeometryVolume occupancy = voxelizeScene(scene, settings);
    const RayTracer tracer(scene);
    for (const Camera& c : views) {
        // Not in the solid block, not within a voxel of any surface, inside the room.
        EXPECT_FALSE(insideBlock(c.eye)) << c.eye.x << " " << c.eye.y << " " << c.eye.z;
        EXPECT_TRUE(glm::all(glm::greaterThan(c.eye, glm::vec3(0.0f))) && glm::all(glm::lessThan(c.eye, glm::vec3(4.0f))));
        const glm::ivec3 v = occupancy.voxelAt(c.eye);
        for (int z = -1; z <= 1; ++z)
            for (int y = -1; y <= 1; ++y)
                for (int x = -1; x <= 1; ++x) EXPECT_FALSE(occupancy.occupied(v + glm::ivec3(x, y, z)));
        // The target is the first surface along the view, far enough to frame something.
        const float distance = glm::length(c.target - c.eye);
        EXPECT_GE(distance, sampling.minTargetDistance * 4.0f);
        const RayHit hit = tracer.intersect(c.eye, (c.target - c.eye) / distance);
        ASSERT_TRUE(hit.hit);
        EXPECT_NEAR(hit.t, distance, 1e-3f * distance);
        EXPECT_TRUE(hit.frontFace);
        // The scene's lens and size are kept.
        EXPECT_EQ(c.width, 32);
        EXPECT_EQ(c.fovYDegrees, scene.camera.fovYDegrees);
    }
}

TEST(ViewSampler, NoEyeInASealedCavity) {
    // The room holds a closed hollow box [0.8, 3.2]^3 whose walls face both ways: from inside
    // it looks like a room (front faces all round), but no light or camera gets in. It fills
    // over a fifth of the room, so without the reachability test about that share of eyes
    // lands inside.
    Scene scene = roomWithBlock();
    scene.meshes.pop_back();
    const glm::mat4 cavity = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(2.0f)), glm::vec3(2.4f));
    scene.meshes.push_back(makeBox(cavity, 0, true));
    scene.meshes.push_back(makeBox(cavity, 0, false));
    view::ViewSampling sampling;
    sampling.count = 24;
    const std::vector<Camera> views = view::sampleViews(scene, sampling);
    ASSERT_EQ(views.size(), 24u);
    for (const Camera& c : views)
        EXPECT_FALSE(glm::all(glm::greaterThan(c.eye, glm::vec3(0.8f))) && glm::all(glm::lessThan(c.eye, glm::vec3(3.2f))))
            << c.eye.x << " " << c.eye.y << " " << c.eye.z;
}

TEST(ViewSampler, SameSeedSameViewsOtherSeedOthers) {
    const Scene scene = roomWithBlock();
    view::ViewSampling sampling;
    sampling.count = 4;
    sampling.seed = 3;
    const std::vector<Camera> a = view::sampleViews(scene, sampling), b = view::sampleViews(scene, sampling);
    sampling.seed = 4;
    const std::vector<Camera> c = view::sampleViews(scene, sampling);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].eye, b[i].eye);
        EXPECT_EQ(a[i].target, b[i].target);
    }
    EXPECT_NE(a[0].eye, c[0].eye);
}

TEST(ViewSampler, AClosedSolidAloneHasNoViewsAndSaysSo) {
    // Only the block: every eye outside it sees the sky through most directions, every eye
    // inside sees back faces.
    Scene scene;
    scene.materials = {Material{}};
    scene.meshes.push_back(makeBox(glm::mat4(1.0f), 0));
    view::ViewSampling sampling;
    sampling.count = 2;
    try {
        view::sampleViews(scene, sampling);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("found only 0 views"), std::string::npos) << e.what();
    }
}

TEST(ViewSampler, ViewsFileRoundTripAndBadFiles) {
    const Scene scene = roomWithBlock();
    view::ViewSampling sampling;
    sampling.count = 3;
    const std::vector<Camera> views = view::sampleViews(scene, sampling);
    const std::string dir = makeTempDir("views-file");
    view::writeViews(dir + "/views.json", views);
    const std::vector<Camera> back = view::readViews(dir + "/views.json", scene);
    ASSERT_EQ(back.size(), views.size());
    for (std::size_t i = 0; i < views.size(); ++i) {
        EXPECT_NEAR(glm::length(back[i].eye - views[i].eye), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(back[i].target - views[i].target), 0.0f, 1e-6f);
    }
    writeFile(dir + "/bad.json", "{\"keys\": [{\"frame\": 0, \"eye\": [0, 1], \"target\": [1, 1, 1]}]}");
    EXPECT_THROW(view::readViews(dir + "/bad.json", scene), InputError);
    writeFile(dir + "/events.json", "{\"events\": [{\"frame\": 0, \"show\": \"probes\"}]}");
    EXPECT_THROW(view::readViews(dir + "/events.json", scene), InputError);
}

TEST(ViewSummary, FractionsQualityAndGainAgainstTheBaselines) {
    auto row = [](std::vector<double> relMse, std::vector<double> meanError) {
        cli::ViewsRow r;
        for (std::size_t k = 0; k < relMse.size(); ++k) {
            cli::ViewScore s;
            s.full.relMse = relMse[k];
            s.full.flip = relMse[k];
            s.full.meanError = meanError[k];
            s.frameMs = double(k + 1);
            r.views.push_back(s);
        }
        return r;
    };
    const cli::ViewsRow direct = row({1.0, 1.0, 1.0, 1.0}, {10.0, 10.0, 10.0, 10.0});
    const cli::ViewsRow ambient = row({0.5, 0.5, 0.5, 0.5}, {5.0, 5.0, 5.0, 5.0});
    const cli::ViewsRow method = row({0.4, 2.0, 0.9, 0.6}, {8.0, 12.0, 10.0, 5.0});
    const cli::ViewSummary v = cli::summarize(method, &direct, &ambient);
    EXPECT_EQ(v.views, 4);
    EXPECT_DOUBLE_EQ(v.relMseMean, 0.975);
    EXPECT_DOUBLE_EQ(v.relMseMedian, 0.75);
    EXPECT_DOUBLE_EQ(v.beatsDirectRelMse, 0.75);  // 0.4, 0.9, 0.6 < 1
    EXPECT_DOUBLE_EQ(v.beatsAmbientRelMse, 0.25);  // 0.4 < 0.5
    EXPECT_DOUBLE_EQ(v.qualityMean, (1.0 - 1.0 + 0.0 + 1.0) / 4.0);  // Eq. 21: +1, -1, 0, +1
    EXPECT_DOUBLE_EQ(v.gainMean, (20.0 - 20.0 + 0.0 + 50.0) / 4.0);
    EXPECT_DOUBLE_EQ(v.frameMsMedian, 2.5);
    // A baseline is not scored against itself.
    EXPECT_TRUE(std::isnan(cli::summarize(direct, &direct, &ambient).beatsDirectFlip));
    EXPECT_TRUE(std::isnan(cli::summarize(direct, &direct, &ambient).qualityMean));
}

TEST(EvalViews, CornellBoxOverViewsWithHeldOutAmbientAndAReplayableViewsFile) {
    const std::string dir = makeTempDir("eval-views");
    const std::string common = " --methods direct,ambient --width 24 --height 24 --spp 4 --frames 3 --warmup 1 --cache " +
                               dir + "/cache";
    RunResult r = runVoxgi("eval cornell-box --views 3 --view-seed 5" + common + " -o " + dir + "/a");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json j = readJson(dir + "/a/views.json");
    const nlohmann::json& scene = j["scenes"][0];
    ASSERT_EQ(scene["views"].size(), 3u);
    ASSERT_EQ(scene["runs"].size(), 3u);  // direct, ambient (oracle fit), ambient (held out)
    EXPECT_EQ(scene["runs"][1]["oracle"], true);
    EXPECT_EQ(scene["runs"][2]["oracle"], false);
    EXPECT_EQ(scene["runs"][2]["held_out"], true);
    for (const nlohmann::json& run : scene["runs"]) {
        ASSERT_EQ(run["views"].size(), 3u);
        EXPECT_LE(run["worst"].size(), 3u);
        for (const nlohmann::json& w : run["worst"]) EXPECT_TRUE(fileExists(dir + "/a/" + w["image"].get<std::string>()));
    }
    // The oracle, fitted to each view, is at least as close as the same constant held out.
    EXPECT_LE(scene["runs"][1]["summary"]["relmse_mean"].get<double>(), scene["runs"][2]["summary"]["relmse_mean"].get<double>());
    std::ifstream md(dir + "/a/views.md");
    const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("ambient (oracle fit)"), std::string::npos);
    EXPECT_NE(text.find("ambient (held out)"), std::string::npos);

    // The written views, given back, are the same views: same references (from the cache), same errors.
    r = runVoxgi("eval cornell-box --views " + dir + "/a/cornell-box/views.json" + common + " -o " + dir + "/b");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("from the cache"), std::string::npos);
    nlohmann::json k = readJson(dir + "/b/views.json");
    for (std::size_t v = 0; v < 3; ++v)
        EXPECT_NEAR(k["scenes"][0]["runs"][0]["views"][v]["full"]["relmse"].get<double>(),
                    scene["runs"][0]["views"][v]["full"]["relmse"].get<double>(), 1e-9);

    // Bad uses: a file for several scenes, a fixed reference, a seed without views.
    EXPECT_EQ(runVoxgi("eval cornell-box cornell-box --views " + dir + "/a/cornell-box/views.json -o " + dir + "/c").exitCode, 2);
    EXPECT_EQ(runVoxgi("eval cornell-box --views 2 --reference x.exr -o " + dir + "/c").exitCode, 2);
    EXPECT_EQ(runVoxgi("eval cornell-box --view-seed 2 -o " + dir + "/c").exitCode, 2);
    EXPECT_EQ(runVoxgi("eval cornell-box --views " + dir + "/missing.json -o " + dir + "/c").exitCode, 2);
    EXPECT_FALSE(fileExists(dir + "/c"));  // read with the other inputs: nothing written
}

// `--views` runs every method but the oracles on one renderer whose camera moves: DDGI's field
// settles once, at the first view, and the next view starts from it; a method without a light
// state renders each view exactly as a fresh run does.
TEST(EvalViews, OneRendererKeepsItsLightStateFromViewToView) {
    useHeadlessContext();
    Scene scene = cornellBox();
    cli::RenderSettings rs;
    rs.width = rs.height = scene.camera.width = scene.camera.height = 16;
    rs.frames = 4;
    rs.warmup = 1;
    rs.convergeBelow = 0.05;
    rs.maxWarmup = 200;
    Camera second = scene.camera;
    second.eye += 0.1f * (second.target - second.eye);
    second.target += glm::vec3(0.05f, 0.0f, 0.0f);

    cli::MethodSession ddgi(scene, "ddgi", Preset{"low", {{"ddgi.rays", "32"}}}, rs);
    const cli::MethodRun first = ddgi.render(scene.camera);
    const cli::MethodRun next = ddgi.render(second);
    EXPECT_TRUE(first.converged);
    EXPECT_GT(first.warmupFrames, 10);  // the change window fills first
    EXPECT_TRUE(next.converged);
    EXPECT_EQ(next.warmupFrames, rs.warmup);

    cli::MethodSession isr(scene, "isr", Preset{"default", {}}, rs);
    isr.render(scene.camera);
    Scene moved = scene;
    moved.camera = second;
    const cli::MethodRun keptRun = isr.render(second);
    const cli::MethodRun freshRun = cli::renderMethod(moved, "isr", Preset{"default", {}}, rs);
    const std::vector<float>& kept = keptRun.image.find("beauty")->data;
    const std::vector<float>& fresh = freshRun.image.find("beauty")->data;
    ASSERT_EQ(kept.size(), fresh.size());
    for (std::size_t i = 0; i < kept.size(); ++i) ASSERT_NEAR(kept[i], fresh[i], 1e-6f * (1.0f + std::abs(fresh[i]))) << i;
}
