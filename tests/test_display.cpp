// How HDR images are shown (shaders/shared/tone_map.h, docs/display.md): the same display
// transform in C++ and GLSL, auto exposure to middle grey on the CPU and on the GPU, eye
// adaptation, the exposure recorded in the EXR header, and the CLI options.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gl/context.h"
#include "gl/program.h"
#include "render/frame/frame_renderer.h"
#include "render/view/display_pass.h"
#include "scenes/image.h"
#include "shaders/shared/tone_map.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {
class DisplayGpu : public ::testing::Test {
protected:
    static void SetUpTestSuite() { test::useHeadlessContext(); }
};
}  // namespace

TEST(DisplayTransform, CurvesAtKnownValues) {
    // The ACES fit at 0.5: 0.5 (2.51 * 0.5 + 0.03) / (0.5 (2.43 * 0.5 + 0.59) + 0.14) = 0.6163...
    const float aces = 0.5f * (2.51f * 0.5f + 0.03f) / (0.5f * (2.43f * 0.5f + 0.59f) + 0.14f);
    EXPECT_NEAR(toneMapToSrgb(glm::vec3(0.5f), 0.0f).g, shading::srgbEncode(aces), 1e-6f);
    EXPECT_NEAR(toneMapToSrgb(glm::vec3(0.25f), 1.0f).g, shading::srgbEncode(aces), 1e-6f);  // one stop up
    // Reinhard on luminance: grey 1 becomes 0.5; a colour keeps its hue (channel ratios).
    EXPECT_NEAR(toneMapToSrgb(glm::vec3(1.0f), 0.0f, shading::kToneReinhard).r, shading::srgbEncode(0.5f), 1e-6f);
    const glm::vec3 c(0.6f, 0.3f, 0.15f);
    const glm::vec3 r = shading::toneCurve(c, shading::kToneReinhard);
    EXPECT_NEAR(r.g / r.r, 0.5f, 1e-6f);
    EXPECT_NEAR(r.b / r.r, 0.25f, 1e-6f);
    EXPECT_EQ(toneMapToSrgb(glm::vec3(NAN, INFINITY, -1.0f), 0.0f), glm::vec3(0.0f));
}

TEST_F(DisplayGpu, GlslTransformMatchesCpp) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> v(0.0f, 8.0f), s(-3.0f, 3.0f);
    std::vector<glm::vec4> in;
    for (int i = 0; i < 512; ++i) in.emplace_back(v(rng), v(rng) * 0.1f, v(rng) * 10.0f, std::exp2(s(rng)));
    gl::Handle values = gl::createBuffer(in.size() * sizeof(glm::vec4), in.data(), 0);
    gl::Handle results = gl::createBuffer(in.size() * sizeof(glm::vec4), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl::Program program = gl::Program::compute("tests/tone_map.comp");
    for (int curve : {shading::kToneFilmic, shading::kToneReinhard}) {
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, values.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, results.id());
        program.use();
        program.set("uCount", int(in.size()));
        program.set("uCurve", curve);
        glDispatchCompute(GLuint((in.size() + 63) / 64), 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<glm::vec4> gpu(in.size());
        glGetNamedBufferSubData(results.id(), 0, GLsizeiptr(gpu.size() * sizeof(glm::vec4)), gpu.data());
        for (std::size_t i = 0; i < in.size(); ++i) {
            const glm::vec3 cpu = toneMapToSrgb(glm::vec3(in[i]), std::log2(in[i].w), curve);
            // Within a quarter of an 8-bit step (GLSL's pow is not glibc's).
            for (int k = 0; k < 3; ++k) ASSERT_NEAR(gpu[i][k], cpu[k], 0.25f / 255.0f) << "curve " << curve << " value " << i;
        }
    }
}

TEST(AutoExposure, LogAverageOfLitPixelsGoesToMiddleGrey) {
    Image image(4, 4);
    ImageLayer& l = image.layer("beauty");
    // 8 pixels at luminance 1, 4 at 4, 4 black (a background without sky: not counted).
    for (int i = 0; i < 16; ++i) {
        const float y = i < 8 ? 1.0f : i < 12 ? 4.0f : 0.0f;
        for (int k = 0; k < 3; ++k) l.data[std::size_t(3 * i + k)] = y;
    }
    const double logAverage = std::exp((8.0 * std::log(1.0) + 4.0 * std::log(4.0)) / 12.0);
    EXPECT_NEAR(autoExposureStops(image), std::log2(0.18 / logAverage), 1e-5);
    EXPECT_EQ(autoExposureStops(Image(2, 2)), 0.0f);  // nothing lit (no beauty layer)
}

TEST(AutoExposure, EyeAdaptationApproachesTheTargetWithoutOvershoot) {
    float e = 0.0f;
    for (int frame = 0; frame < 30; ++frame) {
        const float next = adaptExposure(e, 4.0f, 1.0f / 60.0f, 0.5f);
        EXPECT_GT(next, e);
        EXPECT_LT(next, 4.0f);
        e = next;
    }
    // Half a second at a time constant of half a second: 1 - 1/e of the way.
    EXPECT_NEAR(e, 4.0f * (1.0f - std::exp(-1.0f)), 1e-3f);
    EXPECT_EQ(adaptExposure(1.0f, 4.0f, 0.1f, 0.0f), 4.0f);
}

TEST_F(DisplayGpu, ViewerMeasuresTheExposureTheImageGets) {
    Scene s = test::cornellBox();
    s.camera.width = s.camera.height = 128;
    FrameRenderer r(s, FrameOptions{}, "direct");
    r.renderFrame();
    view::DisplayPass display;
    const std::optional<float> gpu = display.autoExposureStops(r, view::DisplayMode::Beauty);
    ASSERT_TRUE(gpu.has_value());
    // The viewer samples a 64 x 64 grid of the 128^2 image; the image's own uses every pixel.
    EXPECT_NEAR(*gpu, autoExposureStops(r.resolve()), 0.1f);
    EXPECT_FALSE(display.autoExposureStops(r, view::DisplayMode::Albedo).has_value());
}

TEST(DisplayCli, ExposureAndCurveAreWrittenToTheExrHeader) {
    const std::string dir = test::makeTempDir("display-cli");
    auto r = test::runVoxgi("render cornell-box --width 32 --height 32 --frames 1 -o " + dir + "/auto.exr --png " + dir +
                            "/auto.png");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Image automatic = readExr(dir + "/auto.exr");
    ASSERT_TRUE(automatic.display.set);
    EXPECT_NEAR(automatic.display.exposureStops, autoExposureStops(automatic), 1e-5f);
    EXPECT_EQ(automatic.display.toneCurve, shading::kToneFilmic);

    r = test::runVoxgi("render cornell-box --width 32 --height 32 --frames 1 --exposure 1.5 --tonemap reinhard -o " + dir +
                       "/fixed.exr");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Image fixed = readExr(dir + "/fixed.exr");
    EXPECT_FLOAT_EQ(fixed.display.exposureStops, 1.5f);
    EXPECT_EQ(fixed.display.toneCurve, shading::kToneReinhard);

    r = test::runVoxgi("render cornell-box --width 32 --height 32 --tonemap agx -o " + dir + "/bad.exr");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("--tonemap agx: expected filmic or reinhard"), std::string::npos) << r.output;
    EXPECT_FALSE(test::fileExists(dir + "/bad.exr"));
    r = test::runVoxgi("reference cornell-box --width 16 --height 16 --spp 1 --exposure bright -o " + dir + "/bad.exr");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("--exposure"), std::string::npos) << r.output;
}
