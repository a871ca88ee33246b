// The headless EGL context on llvmpipe (or any driver): GL 4.5 core, compute shaders, timer
// queries, shader includes and clear compile errors.
#include <cmath>

#include <gtest/gtest.h>

#include "gl/context.h"
#include "gl/program.h"
#include "gl/resources.h"
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

// GPU samples that cannot be right are NaN; summaries skip them, and say NaN when none is left.
TEST(StageTimerSummary, SkipsSamplesThatAreNotMeasurements) {
    EXPECT_DOUBLE_EQ(gl::summarize({1.0, std::nan(""), 3.0}).median, 2.0);
    EXPECT_DOUBLE_EQ(gl::summarize({1.0, std::nan(""), 3.0}).max, 3.0);
    EXPECT_TRUE(std::isnan(gl::summarize({std::nan("")}).median));
    EXPECT_EQ(gl::summarize({}).median, 0.0);
}
