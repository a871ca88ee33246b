// DDGI on GL: the blend/border kernels and the apply pass against their CPU references, and the
// technique end to end through the CLI (render, and the .vdb dump).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gi/gbuffer_upload.h"
#include "gi/ddgi/ddgi_gpu.h"
#include "gi/ddgi/ddgi_system.h"
#include "gi/ddgi/ddgi_technique.h"
#include "gi/ddgi/probe_sampling.h"
#include "gi/raytrace/ray_tracer.h"
#include "gl/context.h"
#include "shaders/shared/constants.h"
#include "support/test_support.h"
#include "test_ddgi_scenes.h"

using namespace voxgi;

namespace {

using test::descFrom;

std::unique_ptr<gl::Context> g_context;

class DdgiGl : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        if (!g_context) g_context = gl::Context::createHeadless();
    }
};

float maxRelativeDifference(const Atlas& a, const Atlas& b, int channels) {
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.texels.size(); ++i)
        for (int c = 0; c < channels; ++c) {
            float x = a.texels[i][c], y = b.texels[i][c];
            worst = std::max(worst, std::abs(x - y) / (1e-3f + std::max(std::abs(x), std::abs(y))));
        }
    return worst;
}

}  // namespace

TEST_F(DdgiGl, BlendAndBorderMatchTheCpuReference) {
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    auto desc = descFrom({{"probes", "4,3,4"}, {"rays", "64"}, {"scroll", "true"}});
    DdgiSystem cpu(tracer, desc), gpu(tracer, desc);
    DdgiGpu backend(gpu.field());
    glm::vec3 eye(0.1f, 1.0f, 0.0f);
    for (int f = 0; f < 4; ++f) {
        eye.x += 0.3f;  // scrolls every other frame: resets go through the upload path
        cpu.update(eye);
        gpu.update(eye, &backend);
    }
    float irr = maxRelativeDifference(cpu.field().irradiance, gpu.field().irradiance, 3);
    float dist = maxRelativeDifference(cpu.field().distance, gpu.field().distance, 2);
    std::printf("blend parity: irradiance %.2e, distance %.2e (max relative difference)\n", irr, dist);
    EXPECT_LT(irr, 1e-3f);
    EXPECT_LT(dist, 1e-3f);
}

TEST_F(DdgiGl, AtlasesGoUpOnlyAfterCpuWrites) {
    // The GPU copy is read back after every update; the next blend uploads the atlases again
    // only when the CPU changed them since (here: probe planes reset by scrolling).
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, descFrom({{"probes", "4,3,4"}, {"spacing", "0.5"}, {"rays", "64"}, {"scroll", "true"}}));
    DdgiGpu backend(ddgi.field());
    glm::vec3 eye(0.1f, 1.0f, 0.0f);
    ddgi.update(eye, &backend);
    ddgi.update(eye, &backend);
    EXPECT_FALSE(backend.lastTimes().atlasesUploaded);
    const std::uint64_t before = ddgi.field().atlasVersion();
    ddgi.update(eye + glm::vec3(2.0f, 0.0f, 0.0f), &backend);
    EXPECT_GT(ddgi.field().atlasVersion(), before);
    EXPECT_TRUE(backend.lastTimes().atlasesUploaded);
    ddgi.update(eye + glm::vec3(2.0f, 0.0f, 0.0f), &backend);
    EXPECT_FALSE(backend.lastTimes().atlasesUploaded);
}

TEST_F(DdgiGl, ApplyMatchesCpuSamplingWithCascadesAndScrolling) {
    Scene scene = test::openYard();
    RayTracer tracer(scene);
    DdgiSystem ddgi(tracer, descFrom({{"probes", "5,3,5"}, {"spacing", "0.4"}, {"rays", "64"}, {"cascades", "2"},
                                      {"backend", "cpu"}}));
    glm::vec3 eye(0.2f, 1.0f, 0.1f);
    for (int f = 0; f < 5; ++f) ddgi.update(eye += glm::vec3(0.25f, 0.0f, -0.15f));
    const ProbeField& field = ddgi.field();

    // A G-buffer of probe-ray hits (positions on real surfaces, normals toward the probe).
    const int w = 16, h = 16;
    std::vector<glm::vec4> pos(w * h, glm::vec4(0.0f)), nrm(w * h, glm::vec4(0.0f)), alb(w * h), emi(w * h);
    const ProbeTrace& trace = ddgi.lastTrace();
    int k = 0;
    for (int i = 0; i < int(trace.surfels.size()) && k < w * h; i += 7) {
        const ProbeSurfel& s = trace.surfels[std::size_t(i)];
        const int probe = i / trace.stride, ray = i % trace.stride;
        if (trace.work[std::size_t(probe)] == ProbeWork::None || s.distance <= 0.0f || s.distance >= kMissDistance) continue;
        pos[k] = glm::vec4(trace.position(ddgi.lastRays(), probe, ray), 1.0f);
        nrm[k] = glm::vec4(s.normal, 0.5f);
        alb[k] = glm::vec4(0.8f, 0.5f, 0.3f, float(k % 3) * 0.25f);  // metallic
        emi[k] = glm::vec4(0.0f, 0.0f, 0.0f, float(k % 2) * 0.1f);  // specular
        ++k;
    }
    ASSERT_GT(k, 100);
    UploadedGBuffer g = uploadGBuffer(pos, nrm, alb, emi, w, h, eye);
    DdgiGpu gpu(field);
    gpu.apply(field, g.view);
    std::vector<float> result = g.readTarget();

    float worst = 0.0f;
    double total = 0.0;
    for (int i = 0; i < k; ++i) {
        glm::vec3 p(pos[i]), n(nrm[i]);
        glm::vec3 v = glm::normalize(eye - p);
        glm::vec3 e = sampleIrradiance(field, p, n, v);
        glm::vec3 expected = (1.0f - alb[i].w) * (1.0f - emi[i].w) * glm::vec3(alb[i]) / shading::kPi * e;
        for (int c = 0; c < 3; ++c) {
            float got = result[std::size_t(i) * 4 + std::size_t(c)];
            worst = std::max(worst, std::abs(got - expected[c]) / (1e-4f + std::abs(expected[c])));
            total += expected[c];
        }
    }
    std::printf("apply parity over %d pixels: max relative difference %.2e\n", k, worst);
    EXPECT_GT(total, 0.0);
    EXPECT_LT(worst, 2e-3f);
}

TEST_F(DdgiGl, RenderCornellBoxAndDumpProbes) {
    std::string dir = test::makeTempDir("ddgi");
    auto r = test::runVoxgi("render cornell-box --method ddgi --width 64 --height 64 --frames 3 --set ddgi.rays=64 -o " +
                            dir + "/ddgi.exr --timings " + dir + "/t.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(test::fileExists(dir + "/ddgi.exr"));
    auto bad = test::runVoxgi("render cornell-box --method ddgi --set ddgi.rayz=64 -o " + dir + "/bad.exr");
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    EXPECT_NE(bad.output.find("ddgi.rayz"), std::string::npos);
    EXPECT_FALSE(test::fileExists(dir + "/bad.exr"));

    Scene scene = test::cornellBox();
    scene.gi.set("ddgi.rays", "32");
    DdgiTechnique technique(scene);
    std::string vdb = dir + "/probes.vdb";
    technique.dumpVdb(vdb);
    ASSERT_TRUE(test::fileExists(vdb));
    std::string print = VDB_PRINT_PROGRAM;
    if (!print.empty()) {
        FILE* pipe = popen((print + " " + vdb + " 2>&1").c_str(), "r");
        ASSERT_NE(pipe, nullptr);
        std::string text;
        char buf[512];
        while (fgets(buf, sizeof buf, pipe)) text += buf;
        pclose(pipe);
        for (const char* grid : {"probe_position", "probe_offset", "probe_state", "probe_irradiance"})
            EXPECT_NE(text.find(grid), std::string::npos) << text;
    }
}
