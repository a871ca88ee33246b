// The LPV's two back ends and shared math: SH in GLSL vs C++, and GL compute propagation vs
// the CPU reference on the same injected light and geometry (1e-4 relative).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gi/lpv/gl_propagation.h"
#include "gi/lpv/injection.h"
#include "gi/lpv/propagation.h"
#include "gi/sh/sh.h"
#include "gl/context.h"
#include "gl/program.h"
#include "gl/resources.h"

#include "support/test_support.h"

using namespace voxgi;

namespace {
class LpvGl : public ::testing::Test {
protected:
    static void SetUpTestSuite() { test::useHeadlessContext(); }
};
}  // namespace

TEST_F(LpvGl, ShConstantsAgreeBetweenGlslAndCpp) {
    const int count = 256;
    std::vector<glm::vec4> dirs(count);
    std::mt19937 rng(11);
    std::normal_distribution<float> g(0.0f, 1.0f);
    for (auto& d : dirs) d = glm::vec4(glm::normalize(glm::vec3(g(rng), g(rng), g(rng))), 0.0f);
    gl::Handle in = gl::createBuffer(dirs.size() * sizeof(glm::vec4), dirs.data(), 0);
    gl::Handle out = gl::createBuffer(3 * dirs.size() * sizeof(glm::vec4), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl::Program p = gl::Program::compute("tests/sh_values.comp");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    p.use();
    glDispatchCompute(count / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> values(3 * count);
    glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(values.size() * sizeof(glm::vec4)), values.data());
    sh::Sh4 f{{0.7f, -0.2f, 0.4f, 0.1f}};
    for (int i = 0; i < count; ++i) {
        glm::vec3 w(dirs[std::size_t(i)]);
        sh::Sh4 b = sh::basis(w), l = sh::cosineLobe(w);
        for (int k = 0; k < 4; ++k) {
            ASSERT_NEAR(values[3 * std::size_t(i)][k], b[k], 1e-6f);
            ASSERT_NEAR(values[3 * std::size_t(i) + 1][k], l[k], 1e-5f);
        }
        ASSERT_NEAR(values[3 * std::size_t(i) + 2].x, sh::evaluate(f, w), 1e-6f);
        ASSERT_NEAR(values[3 * std::size_t(i) + 2].y, sh::convolveCosine(f, w), 1e-5f);
    }
}

// Resolutions that are and are not whole 8-cell runs of the CPU propagator's SIMD layout.
class LpvGlParity : public LpvGl, public ::testing::WithParamInterface<int> {};

TEST_P(LpvGlParity, PropagationMatchesCpuReference) {
    const int n = GetParam();
    CascadeGrid grid;
    grid.resolution = n;
    grid.cellSize = 0.1f;
    LightVolume injected;
    injected.reset(grid);
    BlockerVolume geometry;
    geometry.reset(grid);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int k = 0; k < 2 * n; ++k) {
        std::size_t i = std::size_t(rng() % grid.cellCount());
        glm::vec3 nrm = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        sh::Sh4 lobe = sh::cosineLobe(nrm);
        glm::vec4 v(lobe.c[0], lobe.c[1], lobe.c[2], lobe.c[3]);
        injected.r[i] += v * 3.0f;
        injected.g[i] += v * 1.0f;
        injected.b[i] += v * 0.25f;
    }
    for (std::size_t i = 0; i < geometry.blocker.size(); i += 7) {
        glm::vec3 nrm = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
        geometry.blocker[i] = fullBlocker(nrm) * (0.5f + 0.5f * std::abs(u(rng)));
        geometry.albedo[i] = glm::vec3(0.8f, 0.5f, 0.2f);
    }
    PropagationOptions options;
    CpuPropagator cpu;
    LightVolume expected;
    cpu.propagate(injected, geometry, 10, options, expected, false);
    GlPropagator gpu(n);
    gpu.propagate(injected, geometry, 10, options);
    LightVolume actual;
    gpu.readBack(actual);
    float scale = 0.0f;
    for (const glm::vec4& v : expected.r) scale = std::max(scale, std::abs(v.x));
    ASSERT_GT(scale, 0.0f);
    const std::vector<glm::vec4>* e[3] = {&expected.r, &expected.g, &expected.b};
    const std::vector<glm::vec4>* a[3] = {&actual.r, &actual.g, &actual.b};
    for (int c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < e[c]->size(); ++i)
            for (int k = 0; k < 4; ++k) {
                float want = (*e[c])[i][k], got = (*a[c])[i][k];
                ASSERT_NEAR(got, want, 1e-4f * (std::abs(want) + 1e-3f * scale)) << "channel " << c << " cell " << i;
            }
}

INSTANTIATE_TEST_SUITE_P(Resolutions, LpvGlParity, ::testing::Values(16, 12, 20));
