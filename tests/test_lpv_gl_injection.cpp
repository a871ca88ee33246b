// The GL back end's GPU injection against the CPU injection (gi/lpv/injection.h) of the same
// reflective shadow maps and G-buffer: light volumes, summed-and-merged blocker volumes and the
// static-blocker merge agree cell by cell; and `voxgi render --method clpv` gives the same
// indirect light with --backend gl as with --backend cpu.
//
// Tolerance: the GPU sums each cell's points in texel order (GL blends in primitive order), the
// CPU order, so differences come only from per-point rounding (division lowered to a reciprocal,
// fused multiply-adds). Each coefficient is held to 1e-4 of the cell's Y00 coefficient plus its
// own magnitude: Y00 is a sum of positive terms and bounds the sum of the absolute band-1
// contributions (|c_1m| <= (A_1 Y_1) / (A_0 Y_00) c_00 = 1.155 c_00 for a cosine lobe), so band-1
// cancellation cannot hide an error, and a cell the CPU leaves empty must be exactly empty.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "gi/lpv/cascades.h"
#include "gi/lpv/gl_injection.h"
#include "gi/lpv/gl_propagation.h"
#include "gi/lpv/injection.h"
#include "gi/lpv/lpv_technique.h"
#include "gi/lpv/rsm.h"
#include "gi/sh/sh.h"
#include "gl/resources.h"
#include "gl/scene_gpu.h"
#include "scenes/image.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

class LpvGlInjection : public ::testing::Test {
protected:
    static void SetUpTestSuite() { test::useHeadlessContext(); }
};

constexpr float kTolerance = 1e-4f;

// Cascades centred in the box, so that even the finest one holds light and walls.
std::vector<CascadePlacement> cornellCascades(const Scene& scene, int resolution) {
    LpvDesc desc = readLpvDesc(scene.gi, true);
    desc.resolution = resolution;
    desc.cascadeBounds = CascadeBounds::Camera;  // nested around a point inside the box, each holding light
    glm::vec3 inside = scene.bounds().center() + glm::vec3(0.03f, -0.05f, 0.02f);
    return placeCascades(desc, scene.bounds(), inside, scene.camera.target - scene.camera.eye);
}

// Asserts `got` matches `want` coefficient by coefficient (see the tolerance note above);
// returns how many samples hold anything.
std::size_t expectSameVolume(const std::vector<glm::vec4>& want, const std::vector<glm::vec4>& got,
                             const std::string& what) {
    EXPECT_EQ(want.size(), got.size()) << what;
    std::size_t occupied = 0, failures = 0;
    for (std::size_t i = 0; i < want.size() && i < got.size(); ++i) {
        if (want[i] != glm::vec4(0.0f)) ++occupied;
        const float scale = std::abs(want[i].x);
        for (int k = 0; k < 4; ++k) {
            const float tol = kTolerance * (std::abs(want[i][k]) + scale);
            if (std::abs(got[i][k] - want[i][k]) > tol && ++failures <= 5)
                ADD_FAILURE() << what << " sample " << i << " coefficient " << k << ": gpu " << got[i][k] << ", cpu "
                              << want[i][k];
        }
    }
    EXPECT_EQ(failures, 0u) << what;
    return occupied;
}

// A G-buffer of synthetic samples (positions on and off the cell-corner half-way planes of the
// finest cascade, random normals, metallic and specular albedos, misses), uploaded in the frame
// renderer's formats.
struct SyntheticGBuffer {
    gl::Handle position, normal, albedo, emission;
    GBufferView view;

    SyntheticGBuffer(const Scene& scene, const CascadeGrid& finest, int width, int height) {
        std::mt19937 rng(17);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        std::normal_distribution<float> g(0.0f, 1.0f);
        const Bounds b = scene.bounds();
        std::vector<glm::vec4> pos(std::size_t(width * height)), nrm(pos.size()), alb(pos.size()), emi(pos.size());
        for (std::size_t i = 0; i < pos.size(); ++i) {
            glm::vec3 p = b.min + glm::vec3(u(rng), u(rng), u(rng)) * b.extent();
            // A third of the samples sit exactly half-way between geometry samples, where the
            // nearest corner is decided by the last bit of p / h.
            if (i % 3 == 0) p = (glm::floor(p / finest.cellSize) + 0.5f) * finest.cellSize;
            pos[i] = glm::vec4(p, u(rng) < 0.9f ? 1.0f : 0.0f);
            nrm[i] = glm::vec4(glm::vec3(g(rng), g(rng), g(rng)) * 0.7f, 0.5f);  // unnormalized on purpose
            alb[i] = glm::vec4(u(rng), u(rng), u(rng), u(rng) < 0.5f ? 0.0f : u(rng));
            emi[i] = glm::vec4(0.0f, 0.0f, 0.0f, u(rng) < 0.5f ? 0.0f : u(rng));  // w = specular
        }
        position = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
        normal = gl::createTexture(GL_TEXTURE_2D, GL_RGBA16F, width, height);
        albedo = gl::createTexture(GL_TEXTURE_2D, GL_RGBA16F, width, height);
        emission = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
        glTextureSubImage2D(position.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, pos.data());
        glTextureSubImage2D(normal.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, nrm.data());
        glTextureSubImage2D(albedo.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, alb.data());
        glTextureSubImage2D(emission.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, emi.data());
        view.position = position.id();
        view.normal = normal.id();
        view.albedo = albedo.id();
        view.emission = emission.id();
        view.width = width;
        view.height = height;
        view.eye = scene.camera.eye;
        view.viewProjection = scene.camera.projection() * scene.camera.view();
        view.fovYDegrees = scene.camera.fovYDegrees;
    }
};

// Random static blockers, a third of them facing against what the dynamic sources left there.
BlockerVolume syntheticStatic(const BlockerVolume& dynamic) {
    BlockerVolume v;
    v.reset(dynamic.grid);
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (std::size_t i = 0; i < v.blocker.size(); i += 5) {
        glm::vec3 n = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(1e-3f));
        const glm::vec4& d = dynamic.blocker[i];
        if (i % 3 == 0 && glm::vec3(d.y, d.z, d.w) != glm::vec3(0.0f)) n = -glm::normalize(glm::vec3(-d.w, -d.y, d.z));
        v.blocker[i] = fullBlocker(n) * (0.5f + 0.5f * std::abs(u(rng)));
        v.albedo[i] = glm::vec3(0.5f + 0.5f * u(rng), 0.3f, 0.5f + 0.4f * u(rng));
    }
    return v;
}

GlCascadeTargets targetsOf(const GlPropagator& p, const CascadeGrid& grid, int set = 0) {
    GlCascadeTargets t;
    t.grid = grid;
    for (int k = 0; k < 3; ++k) t.light[k] = p.injected(k, set);
    t.blocker = p.blocker();
    t.albedo = p.albedo();
    return t;
}

// Injects every face of every light of `scene` and a synthetic G-buffer into 3 cascades both
// ways, the light split between each cascade's ring and inner volumes (gi/lpv/cascades.h); the
// GPU takes the faces `batch` at a time, as the technique does when the maps are large.
void expectGpuInjectionMatchesCpu(const Scene& scene, std::size_t expectedFaces, std::size_t batch) {
    SceneGpu gpu(scene);
    RsmRenderer rsm(96);
    ASSERT_EQ(rsmFaceCount(scene), expectedFaces);
    std::vector<SurfelSource> sources;
    for (const RsmFace& f : rsm.renderToTextures(scene, gpu, 0, expectedFaces)) sources.push_back(readSurfels(f));
    ASSERT_EQ(sources.size(), expectedFaces);

    const int n = 16;
    auto placements = cornellCascades(scene, n);
    ASSERT_EQ(placements.size(), 3u);
    SyntheticGBuffer gbuffer(scene, placements[0].grid, 75, 52);
    const GBufferSampling sampling = GBufferSampling::of(gbuffer.view, 32);
    ASSERT_EQ(sampling.stride, 4);
    const SurfelSource camera = gbufferSurfels(gbuffer.view, 32);
    ASSERT_GT(camera.surfels.size(), 200u);

    // CPU reference.
    InjectionOffsets offsets;
    std::vector<LightVolume> light(placements.size()), inner(placements.size());
    std::vector<BlockerVolume> geometry(placements.size()), statics(placements.size());
    for (std::size_t c = 0; c < placements.size(); ++c) {
        light[c].reset(placements[c].grid);
        inner[c].reset(placements[c].grid);
        for (const SurfelSource& s : sources) injectLight(s, offsets, placements, c, light[c], inner[c]);
        BlockerVolume scratch;
        scratch.reset(placements[c].grid);
        geometry[c].reset(placements[c].grid);
        for (const SurfelSource& s : sources) injectBlockers(s, scratch, geometry[c]);
        injectBlockers(camera, scratch, geometry[c]);
        statics[c] = syntheticStatic(geometry[c]);
        geometry[c].mergeMax(statics[c]);
    }

    // GPU, straight from the textures.
    GlInjector injector(n);
    std::vector<std::unique_ptr<GlPropagator>> volumes;
    for (std::size_t c = 0; c < placements.size(); ++c) {
        volumes.push_back(std::make_unique<GlPropagator>(n, 2));
        GlCascadeTargets t = targetsOf(*volumes[c], placements[c].grid);
        injector.clearLight(t);
        injector.clearLight(targetsOf(*volumes[c], placements[c].grid, 1));
        injector.clearGeometry(t);
    }
    for (std::size_t first = 0; first < expectedFaces; first += batch) {
        const std::vector<RsmFace>& faces = rsm.renderToTextures(scene, gpu, first, batch);
        for (std::size_t c = 0; c < placements.size(); ++c) {
            GlCascadeTargets t = targetsOf(*volumes[c], placements[c].grid);
            const GlCascadeTargets innerTargets = targetsOf(*volumes[c], placements[c].grid, 1);
            for (const RsmFace& f : faces) injector.injectLight(f, offsets, t, placements, c, false);
            for (const RsmFace& f : faces) injector.injectLight(f, offsets, innerTargets, placements, c, true);
            for (const RsmFace& f : faces) injector.injectBlockers(f, t);
        }
    }
    for (std::size_t c = 0; c < placements.size(); ++c) {
        SCOPED_TRACE("cell size " + std::to_string(placements[c].grid.cellSize));
        GlCascadeTargets t = targetsOf(*volumes[c], placements[c].grid);
        GlBlockerVolume staticGpu(n);
        staticGpu.upload(statics[c]);
        injector.injectBlockers(gbuffer.view, sampling, t);
        injector.mergeBlockers(staticGpu, t);
        LightVolume gotLight, gotInner;
        volumes[c]->readBackInjected(gotLight, 0);
        volumes[c]->readBackInjected(gotInner, 1);
        BlockerVolume gotGeometry;
        volumes[c]->readBackGeometry(gotGeometry);

        std::size_t lit = expectSameVolume(light[c].r, gotLight.r, "light r");
        expectSameVolume(light[c].g, gotLight.g, "light g");
        expectSameVolume(light[c].b, gotLight.b, "light b");
        lit += expectSameVolume(inner[c].r, gotInner.r, "inner r");
        expectSameVolume(inner[c].g, gotInner.g, "inner g");
        expectSameVolume(inner[c].b, gotInner.b, "inner b");
        std::size_t blocked = expectSameVolume(geometry[c].blocker, gotGeometry.blocker, "blocker");
        EXPECT_GT(lit, 20u);
        EXPECT_GT(blocked, 200u);
        std::size_t albedoMismatches = 0;
        for (std::size_t i = 0; i < geometry[c].albedo.size(); ++i)
            if (glm::any(glm::greaterThan(glm::abs(gotGeometry.albedo[i] - geometry[c].albedo[i]), glm::vec3(1e-6f))))
                ++albedoMismatches;
        EXPECT_EQ(albedoMismatches, 0u);
    }
}

}  // namespace

TEST_F(LpvGlInjection, QuadLightMatchesCpuInjection) {
    expectGpuInjectionMatchesCpu(test::cornellBox(), 5, 5);  // the quad light's hemicube
}

// Orthographic (sun through the open front), single perspective (spot) and cube (point) maps,
// injected 3 faces at a time.
TEST_F(LpvGlInjection, SunSpotAndPointLightsMatchCpuInjectionInBatches) {
    Scene scene = test::cornellBox();
    scene.lights.clear();
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -0.5f, 1.0f));
    sun.emission = glm::vec3(3.0f, 2.5f, 2.0f);
    Light spot;
    spot.type = LightType::Spot;
    spot.position = glm::vec3(0.4f, 0.5f, 0.35f);
    spot.direction = glm::normalize(glm::vec3(-0.2f, -1.0f, 0.1f));
    spot.emission = glm::vec3(0.5f, 0.8f, 1.0f);
    Light point;
    point.type = LightType::Point;
    point.position = glm::vec3(0.15f, 0.3f, 0.25f);
    point.emission = glm::vec3(0.2f, 0.1f, 0.05f);
    scene.lights = {sun, spot, point};
    expectGpuInjectionMatchesCpu(scene, 8, 3);
}

// Same scene twice through the CLI: the GL back end (RSM, injection, propagation on the GPU)
// against the CPU back end, held to LpvRender.GlBackendMatchesCpuBackendImage's 1e-3.
TEST_F(LpvGlInjection, ClpvRenderMatchesCpuBackend) {
    // Pixel by pixel, not only in the mean: a GL step that averaged each face's corners itself
    // once matched the CPU's mean to 1e-6 with a relMSE of 0.04 between the images (llvmpipe).
    std::string dir = test::makeTempDir("lpv-gl-injection");
    auto indirect = [&](const std::string& backend) {
        std::string out = dir + "/" + backend + ".exr";
        // The SH transport's gl injection and steps (the ordinates': LpvOrdinatesRender).
        auto r = test::runVoxgi("render cornell-box --method clpv --set lpv.transport=sh --backend " + backend +
                                " --width 64 --height 64 --frames 1 -o " + out);
        EXPECT_EQ(r.exitCode, 0) << r.output;
        Image img = readExr(out);
        const ImageLayer* layer = img.find("indirect");
        EXPECT_NE(layer, nullptr);
        return layer ? layer->data : std::vector<float>{};
    };
    const std::vector<float> cpu = indirect("cpu"), gl = indirect("gl");
    ASSERT_EQ(cpu.size(), gl.size());
    ASSERT_FALSE(cpu.empty());
    double sum = 0.0, glSum = 0.0, largest = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < cpu.size(); ++i) {
        sum += cpu[i];
        glSum += gl[i];
        largest = std::max(largest, double(std::abs(cpu[i])));
        worst = std::max(worst, double(std::abs(gl[i] - cpu[i])));
    }
    ASSERT_GT(sum, 0.0);
    std::printf("clpv indirect mean: cpu %.6g, gl %.6g (ratio %.6f); largest pixel difference %.3g of the largest value\n",
                sum / double(cpu.size()), glSum / double(gl.size()), glSum / sum, worst / largest);
    EXPECT_NEAR(glSum / sum, 1.0, 1e-3);
    EXPECT_LT(worst / largest, 1e-4);
}
