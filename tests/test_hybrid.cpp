// The hybrid method (gi/hybrid/): mirror-like lobes traced with Embree, the surfaces they reach
// lit by the frame's passes, composited with Fresnel. Analytic cases: a perfect mirror shows the
// emitter above it at its full radiance; a glass slab passes (1 - F)^2 of the emitter below it,
// and nothing when the depth stops the ray inside the glass; without mirror-like materials the
// method is the rasterized frame and its diffuse method, pixel for pixel.
#include <gtest/gtest.h>

#include <cmath>

#include "gi/hybrid/mirror_paths.h"
#include "gi/pathtrace/bsdf.h"
#include "render/frame/frame_plan.h"
#include "render/frame/frame_renderer.h"
#include "scenes/scene_loader.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

class Hybrid : public ::testing::Test {
protected:
    static void SetUpTestSuite() { test::useHeadlessContext(); }
};

Image render(const Scene& scene, const std::string& method, int frames) {
    FrameRenderer r(scene, FrameOptions{}, planFrame(scene, method, frames));
    for (int i = 0; i < frames; ++i) r.renderFrame();
    return r.resolve();
}

// Mean of the beauty layer over the (2 half + 1)^2 pixels around the image's centre.
glm::vec3 centre(const Image& img, int half) {
    glm::dvec3 sum(0.0);
    int n = 0;
    for (int y = img.height() / 2 - half; y <= img.height() / 2 + half; ++y)
        for (int x = img.width() / 2 - half; x <= img.width() / 2 + half; ++x, ++n) sum += glm::dvec3(img.rgb("beauty", x, y));
    return glm::vec3(sum / double(n));
}

// A camera 1 m above y = 0 looking straight down, over `meshes`, with `materials`.
Scene lookingDown(const std::string& materials, const std::string& meshes, int depth) {
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [0, 1, 0.0001], "target": [0, 0, 0], "fov": 20, "resolution": [32, 32], "near": 0.01, "far": 10},
      "materials": {)" + materials + R"(},
      "meshes": [)" + meshes + R"(]
    })", "hybrid-test.json");
    s.gi.set("hybrid.diffuse", "none");
    s.gi.set("hybrid.depth", std::to_string(depth));
    return s;
}

}  // namespace

TEST(MirrorPaths, OnlySmoothCoatsMetalsAndGlassAreTraced) {
    shading::GBufferSurface s{};
    s.roughness = 0.0f;
    EXPECT_FALSE(tracesMirrorLobe(s));  // smooth but Lambert only
    s.specular = 0.04f;
    EXPECT_TRUE(tracesMirrorLobe(s));
    s.roughness = 0.2f;
    EXPECT_FALSE(tracesMirrorLobe(s));  // rough: the rasterized GGX highlight
    s = shading::GBufferSurface{};
    s.roughness = 0.0f;
    s.transmission = 1.0f;
    EXPECT_TRUE(tracesMirrorLobe(s));
    s.metallic = 1.0f;
    s.transmission = 0.0f;
    EXPECT_TRUE(tracesMirrorLobe(s));
}

// An emitter 2 m above a perfect mirror (a metal of albedo 1: Fresnel 1 at every angle): every
// mirror pixel shows the emitter's radiance, in the direct layer (one scattering).
TEST_F(Hybrid, PerfectMirrorShowsTheEmitterAbove) {
    const Scene s = lookingDown(R"("mirror": {"albedo": [1, 1, 1], "metallic": 1, "roughness": 0},
                                   "lamp": {"albedo": [0, 0, 0], "emission": [2, 1, 0.5]})",
                                R"({"type": "quad", "name": "mirror", "material": "mirror",
                                    "corners": [[-5, 0, -5], [-5, 0, 5], [5, 0, 5], [5, 0, -5]]},
                                   {"type": "quad", "name": "lamp", "material": "lamp",
                                    "corners": [[-50, 3, -50], [50, 3, -50], [50, 3, 50], [-50, 3, 50]]})",
                                3);
    const Image hybrid = render(s, "hybrid", 1);
    const glm::vec3 c = centre(hybrid, 8);
    EXPECT_NEAR(c.r, 2.0f, 0.01f);
    EXPECT_NEAR(c.g, 1.0f, 0.005f);
    EXPECT_NEAR(c.b, 0.5f, 0.0025f);
    EXPECT_NEAR(hybrid.rgb("direct", 16, 16).r, 2.0f, 0.01f);
    EXPECT_NEAR(hybrid.rgb("indirect", 16, 16).r, 0.0f, 1e-6f);
    // The rasterized frame alone shades the mirror black: it has no diffuse lobe and no light.
    EXPECT_NEAR(centre(render(s, "direct", 1), 8).r, 0.0f, 1e-6f);
}

// Without the hybrid method a mirror still shows a quad light where its reflected ray meets it,
// every frame (not a GGX spike at one point of the quad a frame): a perfect mirror under a 2 m
// quad light of radiance (3, 2, 1) shows (3, 2, 1) in the middle, from the first frame on.
TEST_F(Hybrid, MirrorShowsAQuadLightInTheRasterizedFrame) {
    Scene s = lookingDown(R"("mirror": {"albedo": [1, 1, 1], "metallic": 1, "roughness": 0})",
                          R"({"type": "quad", "name": "mirror", "material": "mirror",
                              "corners": [[-5, 0, -5], [-5, 0, 5], [5, 0, 5], [5, 0, -5]]})",
                          3);
    Light quad;
    quad.type = LightType::Quad;
    quad.position = {-1.0f, 3.0f, -1.0f};
    quad.edgeU = {2.0f, 0.0f, 0.0f};
    quad.edgeV = {0.0f, 0.0f, 2.0f};
    quad.emission = {3.0f, 2.0f, 1.0f};
    ASSERT_LT(quad.quadNormal().y, 0.0f);  // emitting downwards
    s.lights.push_back(quad);
    s.addQuadLightGeometry();
    for (int frames : {1, 4}) {
        const glm::vec3 c = centre(render(s, "direct", frames), 2);
        EXPECT_NEAR(c.r, 3.0f, 0.03f) << frames;
        EXPECT_NEAR(c.g, 2.0f, 0.02f) << frames;
        EXPECT_NEAR(c.b, 1.0f, 0.01f) << frames;
    }
}

// Glass (transmission 1, ior 1.5, clear) 0.1 m thick over an emitter: near normal incidence
// the camera sees (1 - F)^2 of it with F = ((1.5 - 1) / (1.5 + 1))^2 = 0.04, the radiance scaled
// by eta^2 going in and 1 / eta^2 coming out. Depth 1 stops the ray inside the glass.
TEST_F(Hybrid, GlassSlabPassesWhatFresnelLeaves) {
    const std::string materials = R"("glass": {"albedo": [1, 1, 1], "transmission": 1, "ior": 1.5, "roughness": 0},
                                     "lamp": {"albedo": [0, 0, 0], "emission": [1, 1, 1]})";
    const std::string meshes = R"({"type": "box", "name": "slab", "material": "glass",
                                   "transform": {"scale": [4, 0.1, 4], "translate": [0, 0.5, 0]}},
                                  {"type": "quad", "name": "lamp", "material": "lamp",
                                   "corners": [[-50, 0, -50], [-50, 0, 50], [50, 0, 50], [50, 0, -50]]})";
    const float F = pt::fresnelDielectric(1.0f, 1.0f / 1.5f);
    ASSERT_NEAR(F, 0.04f, 1e-6f);
    // Past the first interface one lobe is followed at random; the frames average the choices.
    const Image through = render(lookingDown(materials, meshes, 3), "hybrid", 32);
    const glm::vec3 c = centre(through, 3);
    EXPECT_NEAR(c.g, (1.0f - F) * (1.0f - F), 0.015f);
    const Image stopped = render(lookingDown(materials, meshes, 1), "hybrid", 1);
    EXPECT_NEAR(centre(stopped, 3).g, 0.0f, 1e-6f);
}

// Without mirror-like materials the method plans none of its passes and renders what its
// diffuse method renders.
TEST_F(Hybrid, WithoutMirrorsItIsItsDiffuseMethod) {
    Scene s = test::cornellBox();
    s.camera.width = s.camera.height = 32;
    s.gi.set("hybrid.diffuse", "lpv");
    const FramePlan plan = planFrame(s, "hybrid", 1);
    EXPECT_FALSE(plan.runs("hybrid.trace"));
    EXPECT_TRUE(plan.runs("lpv.apply"));
    const Image hybrid = render(s, "hybrid", 2), lpv = render(s, "lpv", 2);
    const std::vector<float>& a = hybrid.find("beauty")->data;
    const std::vector<float>& b = lpv.find("beauty")->data;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << i;
}
