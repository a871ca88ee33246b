// The headless EGL context on llvmpipe (or any driver): GL 4.5 core, compute shaders, timer
// queries, shader includes and clear compile errors; reading results back frames later.
#include <cmath>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gl/program.h"
#include "gl/readback_ring.h"
#include "gl/resources.h"
#include "gl/screen_pass.h"
#include "gl/timers.h"
#include "shaders/shared/constants.h"

using namespace voxgi;

class GlContext : public ::testing::Test {
protected:
    static void SetUpTestSuite() { context_ = gl::Context::createHeadless().release(); }
    static void TearDownTestSuite() {
        delete context_;
        context_ = nullptr;
    }
    static gl::Context* context_;
};
gl::Context* GlContext::context_ = nullptr;

TEST_F(GlContext, IsGl45Core) {
    GLint major = 0, minor = 0, mask = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    EXPECT_GE(major * 10 + minor, 45);
    EXPECT_TRUE(mask & GL_CONTEXT_CORE_PROFILE_BIT);
    EXPECT_NE(context_->description().find("EGL"), std::string::npos) << context_->description();
}

TEST_F(GlContext, ComputeShaderWithIncludeWritesBuffer) {
    gl::Program p = gl::Program::compute("tests/fill.comp", {{"FILL_SCALE", "3.0"}});
    gl::Handle buffer = gl::createBuffer(64 * sizeof(float), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer.id());
    gl::StageTimers timers;
    timers.begin("fill");
    p.use();
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    timers.end();
    timers.collect();
    std::vector<float> out(64);
    glGetNamedBufferSubData(buffer.id(), 0, 64 * sizeof(float), out.data());
    for (int i = 0; i < 64; ++i) ASSERT_FLOAT_EQ(out[std::size_t(i)], 3.0f * float(i) * shading::kPi);
    ASSERT_EQ(timers.samples().at("fill").gpuMs.size(), 1u);
    EXPECT_GE(timers.samples().at("fill").gpuMs[0], 0.0);
    EXPECT_NE(timers.toJson().find("\"fill\""), std::string::npos);
}

TEST_F(GlContext, CompileErrorNamesTheFile) {
    try {
        gl::Program::compute("tests/broken.comp");
        FAIL() << "expected a compile error";
    } catch (const gl::GlError& e) {
        EXPECT_NE(std::string(e.what()).find("tests/broken.comp"), std::string::npos) << e.what();
    }
    EXPECT_THROW(gl::Program::compute("tests/absent.comp"), gl::GlError);
}

TEST_F(GlContext, EveryShaderInTheTreeCompiles) {
    // The frame passes are linked in pairs; compile each here so a broken shader fails fast.
    EXPECT_NO_THROW(gl::Program::graphics("frame/gbuffer.vert", "frame/gbuffer.frag"));
    EXPECT_NO_THROW(gl::Program::graphics("frame/shadow.vert", "frame/shadow_distance.frag"));
    EXPECT_NO_THROW(gl::Program::graphics("frame/shadow.vert", "frame/shadow_depth.frag"));
    EXPECT_NO_THROW(gl::Program::compute("frame/direct_light.comp"));
    EXPECT_NO_THROW(gl::Program::compute("frame/emission.comp"));
}

// A compute pass adds into the bound target as an additive full-screen draw would: every pixel of
// the viewport within the scissor box once (odd sizes: the last groups' spare invocations write
// nothing), the pixels outside untouched; targets it cannot add into are refused.
TEST_F(GlContext, ScreenPassAddsIntoTheBoundTargetWithinViewportAndScissor) {
    const int w = 13, h = 11;
    gl::Handle target = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, w, h);
    gl::Handle framebuffer = gl::createFramebuffer({target.id()}, 0, "screen pass test");
    const float one[4] = {1, 1, 1, 1};
    glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 0, one);
    gl::Program pass = gl::Program::compute("tests/add_pixel.comp");
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glViewport(0, 0, w, h);
    gl::addToBoundTarget(pass);
    glEnable(GL_SCISSOR_TEST);
    glScissor(3, 2, 5, 20);  // reaches past the top: clipped to the viewport
    gl::addToBoundTarget(pass);
    glDisable(GL_SCISSOR_TEST);
    const std::vector<float> texels = gl::readTexture(target.id(), w, h, 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float times = (x >= 3 && x < 8 && y >= 2) ? 2.0f : 1.0f;
            const float* t = &texels[(std::size_t(y) * w + std::size_t(x)) * 4];
            EXPECT_EQ(t[0], 1.0f + times * float(x)) << x << "," << y;
            EXPECT_EQ(t[1], 1.0f + times * float(y)) << x << "," << y;
            EXPECT_EQ(t[2], 1.0f + times) << x << "," << y;
            EXPECT_EQ(t[3], 1.0f + 2.0f * times) << x << "," << y;
        }
    gl::Handle bytes = gl::createTexture(GL_TEXTURE_2D, GL_RGBA8, w, h);
    gl::Handle bytesFramebuffer = gl::createFramebuffer({bytes.id()}, 0, "screen pass RGBA8 target");
    glBindFramebuffer(GL_FRAMEBUFFER, bytesFramebuffer.id());
    EXPECT_THROW(gl::addToBoundTarget(pass), gl::GlError);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    EXPECT_THROW(gl::addToBoundTarget(pass), gl::GlError);
}

// GPU samples that cannot be right are NaN; summaries skip them, and say NaN when none is left.
TEST(StageTimerSummary, SkipsSamplesThatAreNotMeasurements) {
    EXPECT_DOUBLE_EQ(gl::summarize({1.0, std::nan(""), 3.0}).median, 2.0);
    EXPECT_DOUBLE_EQ(gl::summarize({1.0, std::nan(""), 3.0}).max, 3.0);
    EXPECT_TRUE(std::isnan(gl::summarize({std::nan("")}).median));
    EXPECT_EQ(gl::summarize({}).median, 0.0);
}

// Counters a kernel wrote, read back later without a wait: every push's bytes come back whole,
// tagged with their push; finish() brings the last; more pushes than slots wait for the oldest.
TEST_F(GlContext, ReadbackRingHandsBackEachPushWholeAndTheNewestLast) {
    gl::Handle counters = gl::createBuffer(2 * sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl::Handle more = gl::createBuffer(sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl::ReadbackRing ring(3 * sizeof(GLuint), 3);
    std::uint64_t tag = 0;
    GLuint out[3] = {};
    EXPECT_FALSE(ring.latest(tag, out));  // nothing pushed yet
    std::uint64_t lastTag = 0;
    for (GLuint push = 1; push <= 10; ++push) {
        const GLuint values[2] = {push, 100 + push}, third = 1000 + push;
        glNamedBufferSubData(counters.id(), 0, sizeof(values), values);
        glNamedBufferSubData(more.id(), 0, sizeof(third), &third);
        ring.push(push, {{counters.id(), 0, sizeof(values)}, {more.id(), 0, sizeof(third)}});
        if (ring.latest(tag, out)) {
            EXPECT_GT(tag, lastTag);  // newer than what came back before, never later than the push
            EXPECT_LE(tag, push);
            EXPECT_EQ(out[0], GLuint(tag));
            EXPECT_EQ(out[1], 100 + GLuint(tag));
            EXPECT_EQ(out[2], 1000 + GLuint(tag));
            lastTag = tag;
        }
    }
    ASSERT_TRUE(ring.finish(tag, out) || lastTag == 10);
    if (lastTag != 10) {
        EXPECT_EQ(tag, 10u);
        EXPECT_EQ(out[0], 10u);
        EXPECT_EQ(out[2], 1010u);
    }
    EXPECT_FALSE(ring.latest(tag, out));  // nothing newer since
    EXPECT_THROW(ring.push(11, {{counters.id(), 0, 2 * sizeof(GLuint)}, {counters.id(), 0, 2 * sizeof(GLuint)}}),
                 std::logic_error);
}
