// voxgi eval: the ambient baseline's fit, and report generation on a tiny Cornell box.
#include <cmath>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gi/ambient/ambient_fit.h"
#include "support/test_support.h"

using namespace voxgi;
using namespace voxgi::test;

namespace {
nlohmann::json readJson(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

std::string readText(const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
}
}  // namespace

// The rendered indirect is k * E per pixel and channel; a reference built as k * E_true (plus
// zero-mean noise that cancels exactly in the sums) must give back E_true, and the fitted image's
// mean must equal the reference's.
TEST(AmbientFit, ExactOnSyntheticImage) {
    const int pixels = 36;  // even: the noise comes in +-d pairs
    const glm::vec3 truth(0.7f, 2.5f, 11.0f);
    ImageLayer unit{"indirect", 3, {}}, reference{"indirect", 3, {}};
    for (int i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c) {
            float k = 0.05f + 0.3f * float((i * 7 + c * 3) % 11) / 11.0f;
            unit.data.push_back(k);
            // Pixels 2m and 2m+1 carry +d and -d: the sums, and so the fit, do not see it.
            float noise = (i % 2 == 0 ? 1.0f : -1.0f) * 0.01f * float(i / 2 + 1);
            reference.data.push_back(k * truth[c] + noise);
        }
    glm::vec3 e = fitAmbientIrradiance(unit, reference);
    for (int c = 0; c < 3; ++c) {
        double sumK = 0.0, sumR = 0.0;
        for (int i = 0; i < pixels; ++i) {
            sumK += unit.data[std::size_t(3 * i + c)];
            sumR += reference.data[std::size_t(3 * i + c)];
        }
        EXPECT_NEAR(double(e[c]) * sumK, sumR, 1e-5 * std::abs(sumR)) << "channel " << c;
        EXPECT_NEAR(e[c], truth[c], 1e-4f * truth[c]) << "channel " << c;
    }
}

TEST(AmbientFit, NoiseFreeRecoversIrradianceAndSkipsNonFinite) {
    ImageLayer unit{"indirect", 3, {0.1f, 0.2f, 0.3f, 0.0f, 0.0f, 0.0f, 0.25f, 0.5f, 0.125f}};
    ImageLayer reference{"indirect", 3, {0.3f, 0.4f, 0.3f, NAN, 0.0f, 0.0f, 0.75f, 1.0f, 0.125f}};
    glm::vec3 e = fitAmbientIrradiance(unit, reference);
    EXPECT_FLOAT_EQ(e.r, 3.0f);
    EXPECT_FLOAT_EQ(e.g, 2.0f);
    EXPECT_FLOAT_EQ(e.b, 1.0f);
    ImageLayer wrongSize{"indirect", 3, {1.0f, 1.0f, 1.0f}};
    EXPECT_THROW(fitAmbientIrradiance(unit, wrongSize), std::exception);
}

TEST(Eval, ReportOnTinyCornellBoxWithTwoMethods) {
    std::string dir = makeTempDir("eval-report");
    RunResult r = runVoxgi("eval cornell-box --methods direct,ambient --width 24 --height 24 --spp 8 --frames 6 "
                           "--warmup 2 -o " + dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* f : {"report.md", "report.json", "results.csv", "cornell-box/reference.png",
                          "cornell-box/direct.png", "cornell-box/ambient-flip.png", "cornell-box/crops.png"})
        EXPECT_TRUE(fileExists(dir + "/" + f)) << f;
    nlohmann::json j = readJson(dir + "/report.json");
    ASSERT_EQ(j["scenes"].size(), 1u);
    const auto& scene = j["scenes"][0];
    // The reference against itself: no error at all.
    EXPECT_EQ(scene["reference_self"]["full"]["rmse"].get<double>(), 0.0);
    EXPECT_EQ(scene["reference_self"]["full"]["flip"].get<double>(), 0.0);
    EXPECT_EQ(scene["reference_self"]["indirect"]["rmse"].get<double>(), 0.0);
    EXPECT_EQ(scene["reference"]["spp"].get<int>(), 8);
    ASSERT_EQ(scene["runs"].size(), 2u);
    for (const auto& run : scene["runs"]) {
        for (const char* layer : {"full", "indirect"})
            for (const char* m : {"rmse", "relmse", "mae"}) {
                ASSERT_TRUE(run[layer][m].is_number()) << run[layer].dump();
                double v = run[layer][m].get<double>();
                EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << layer << " " << m;
            }
        EXPECT_TRUE(std::isfinite(run["frame_ms"].get<double>()));
        EXPECT_EQ(run["timed_frames"].get<int>(), 4);
    }
    // Direct light only: the indirect layer is black, so its error is the reference's RMS.
    const auto& direct = scene["runs"][0];
    EXPECT_EQ(direct["method"], "direct");
    for (int c = 0; c < 3; ++c) EXPECT_EQ(direct["mean_indirect"][c].get<double>(), 0.0);
    // The ambient baseline's fitted image has the reference's mean indirect light, per colour,
    // and beats direct light on the indirect layer.
    const auto& ambient = scene["runs"][1];
    EXPECT_EQ(ambient["method"], "ambient");
    for (int c = 0; c < 3; ++c) {
        double want = scene["reference_mean_indirect"][c].get<double>();
        EXPECT_GT(want, 0.0);
        EXPECT_NEAR(ambient["mean_indirect"][c].get<double>(), want, 2e-3 * want) << "channel " << c;
    }
    EXPECT_LT(ambient["indirect"]["rmse"].get<double>(), direct["indirect"]["rmse"].get<double>());
    // A second run reuses the cached reference.
    RunResult again = runVoxgi("eval cornell-box --methods direct --width 24 --height 24 --spp 8 --frames 6 -o " + dir);
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_TRUE(readJson(dir + "/report.json")["scenes"][0]["reference"]["cached"].get<bool>());
    EXPECT_TRUE(readJson(dir + "/report.json")["scenes"][0]["reference"]["caustics"].get<bool>());
    // A reference without caustics is another reference, cached under its own name, and the
    // report says which it is.
    RunResult plain = runVoxgi("eval cornell-box --methods direct --width 24 --height 24 --spp 8 --frames 6 --no-caustics -o " + dir);
    ASSERT_EQ(plain.exitCode, 0) << plain.output;
    const nlohmann::json reference = readJson(dir + "/report.json")["scenes"][0]["reference"];
    EXPECT_FALSE(reference["cached"].get<bool>());
    EXPECT_FALSE(reference["caustics"].get<bool>());
    EXPECT_NE(reference["path"].get<std::string>().find("nocaustics"), std::string::npos);
    EXPECT_NE(readText(dir + "/report.md").find("path traced without caustics"), std::string::npos);
}

TEST(Eval, TemporalMethodsWarmUpUntilTheirLightSettles) {
    std::string dir = makeTempDir("eval-converge");
    RunResult r = runVoxgi("eval cornell-box --methods direct,ddgi --presets low --width 16 --height 16 --spp 4 "
                           "--frames 6 --warmup 2 --converge 0.05 --max-warmup 200 -o " + dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json runs = readJson(dir + "/report.json")["scenes"][0]["runs"];
    ASSERT_EQ(runs.size(), 2u);
    // Direct light starts over every frame: the fixed warm-up.
    EXPECT_FALSE(runs[0]["temporal"].get<bool>());
    EXPECT_EQ(runs[0]["warmup_frames"].get<int>(), 2);
    // DDGI's field needs its window filled and then settles well before the cap.
    EXPECT_TRUE(runs[1]["temporal"].get<bool>());
    EXPECT_TRUE(runs[1]["converged"].get<bool>());
    EXPECT_GT(runs[1]["warmup_frames"].get<int>(), 10);  // DdgiSystem::kChangeWindow
    EXPECT_LT(runs[1]["warmup_frames"].get<int>(), 200);
    EXPECT_EQ(runs[1]["timed_frames"].get<int>(), 4);
    EXPECT_GT(runs[1]["converge_ms"].get<double>(), 0.0);
    // A cap below the window stops the warm-up there, and the row says it did not converge.
    r = runVoxgi("eval cornell-box --methods ddgi --presets low --width 16 --height 16 --spp 4 --frames 6 "
                 "--warmup 2 --max-warmup 5 -o " + dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json capped = readJson(dir + "/report.json")["scenes"][0]["runs"][0];
    EXPECT_FALSE(capped["converged"].get<bool>());
    EXPECT_EQ(capped["warmup_frames"].get<int>(), 5);
}

TEST(Eval, BadOptionsAreOneLineErrors) {
    std::string dir = makeTempDir("eval-bad");
    EXPECT_EQ(runVoxgi("eval cornell-box --methods direct --presets ultra -o " + dir).exitCode, 2);
    EXPECT_EQ(runVoxgi("eval cornell-box --methods magic -o " + dir).exitCode, 2);
    EXPECT_EQ(runVoxgi("eval cornell-box --methods ilpv -o " + dir).exitCode, 3);
    EXPECT_EQ(runVoxgi("eval cornell-box --methods direct").exitCode, 2);
    EXPECT_EQ(runVoxgi("eval cornell-box --methods ddgi --converge 2 -o " + dir).exitCode, 2);
    EXPECT_EQ(runVoxgi("eval --stability --cases no-such-case -o " + dir).exitCode, 2);
    EXPECT_EQ(runVoxgi("eval cornell-box --methods direct --reference ref.exr --no-caustics -o " + dir).exitCode, 2);
    EXPECT_FALSE(fileExists(dir + "/report.json"));
    // Bad input leaves no output folder.
    EXPECT_EQ(runVoxgi("eval no-such-scene.json -o " + dir + "/new").exitCode, 2);
    EXPECT_FALSE(fileExists(dir + "/new"));
}
