// The hybrid method (gi/hybrid/): mirror-like lobes traced with Embree, the surfaces they reach
// lit by the frame's passes, composited with Fresnel. Analytic cases: a perfect mirror shows the
// emitter above it at its full radiance; a glass slab passes (1 - F)^2 of the emitter below it,
// and nothing when the depth stops the ray inside the glass; without mirror-like materials the
// method is the rasterized frame and its diffuse method, pixel for pixel.
#include <gtest/gtest.h>

#include <algorithm>
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

// A 10 x 10 m floor at y = 0 of `material` (facing up), as a mesh of lookingDown.
std::string floorOf(const std::string& material) {
    return R"({"type": "quad", "name": "floor", "material": ")" + material +
           R"(", "corners": [[-5, 0, -5], [-5, 0, 5], [5, 0, 5], [5, 0, -5]]})";
}

// A 2 x 2 m quad light of radiance (3, 2, 1) 3 m above the origin, emitting downwards, with its
// emitting geometry.
void addQuadLightAbove(Scene& s) {
    Light quad;
    quad.type = LightType::Quad;
    quad.position = {-1.0f, 3.0f, -1.0f};
    quad.edgeU = {2.0f, 0.0f, 0.0f};
    quad.edgeV = {0.0f, 0.0f, 2.0f};
    quad.emission = {3.0f, 2.0f, 1.0f};
    ASSERT_LT(quad.quadNormal().y, 0.0f);
    s.lights.push_back(quad);
    s.addQuadLightGeometry();
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
                                floorOf("mirror") + R"(,
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
                          floorOf("mirror"),
                          3);
    addQuadLightAbove(s);
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

namespace {

// The directional albedo of a material's BSDF seen from `wo` (n = +z): the integral of
// f cos over the hemisphere, by a stratified uniform grid in (cos theta, phi).
glm::vec3 hemisphereIntegral(const pt::Bsdf& bsdf, int steps) {
    glm::dvec3 sum(0.0);
    for (int i = 0; i < steps; ++i)
        for (int j = 0; j < steps; ++j) {
            const float z = (float(i) + 0.5f) / float(steps), phi = 2.0f * 3.14159265f * (float(j) + 0.5f) / float(steps);
            const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
            sum += glm::dvec3(bsdf.eval(glm::vec3(r * std::cos(phi), r * std::sin(phi), z)));
        }
    return glm::vec3(sum * (2.0 * 3.14159265358979 / double(steps) / double(steps)));
}

Material roughMetal(float roughness) {
    Material m;
    m.albedo = glm::vec3(1.0f);
    m.metallic = 1.0f;
    m.roughness = roughness;
    return m;
}

}  // namespace

// The glossy lobe's own sampling (the hybrid method's rays): its weights average to the lobe's
// directional albedo, integrated independently from eval, and its density is the BSDF's (a
// metal has no other lobe).
TEST(GlossySampling, WeightsAverageToTheLobesAlbedo) {
    for (const float roughness : {0.1f, 0.3f}) {
        const Material m = roughMetal(roughness);
        const glm::vec3 wo = glm::normalize(glm::vec3(0.5f, 0.0f, 0.866f));
        const pt::Bsdf bsdf(m, m.albedo, wo, glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), true);
        const int n = 400;
        double mean = 0.0;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                pt::BsdfSample s;
                if (!bsdf.sampleGlossy(glm::vec2((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n)), s)) continue;
                mean += s.weight.g;
                // The same density, up to the half vector rebuilt from the reflected direction in floats.
                if ((i * n + j) % 997 == 0) {
                    EXPECT_NEAR(s.pdf, bsdf.pdf(s.direction), 5e-3f * s.pdf) << roughness;
                }
            }
        mean /= double(n) * double(n);
        const float expected = hemisphereIntegral(bsdf, 2000).g;
        EXPECT_GT(expected, 0.8f) << roughness;
        EXPECT_NEAR(mean, expected, 0.005 * expected) << roughness;
    }
}

namespace {
// A rough metal floor (albedo 1) seen from 1 m above, under a square emitter of half width
// `lampHalf` and radiance `emission` (JSON) at 3 m.
Scene glossyFloor(float roughness, int denoiseRadius, float lampHalf, const std::string& emission) {
    const std::string h = std::to_string(lampHalf);
    Scene s = lookingDown(R"("metal": {"albedo": [1, 1, 1], "metallic": 1, "roughness": )" + std::to_string(roughness) + R"(},
                             "lamp": {"albedo": [0, 0, 0], "emission": )" + emission + "}",
                          floorOf("metal") + R"(,
                             {"type": "quad", "name": "lamp", "material": "lamp",
                              "corners": [[-)" + h + ", 3, -" + h + "], [" + h + ", 3, -" + h + "], [" + h + ", 3, " + h +
                              "], [-" + h + ", 3, " + h + "]]}",
                          3);
    s.gi.set("hybrid.denoise_radius", std::to_string(denoiseRadius));
    return s;
}

// Standard deviation of the green channel over the (2 half + 1)^2 pixels around the centre.
float centreSpread(const Image& img, int half) {
    double sum = 0.0, squares = 0.0;
    int n = 0;
    for (int y = img.height() / 2 - half; y <= img.height() / 2 + half; ++y)
        for (int x = img.width() / 2 - half; x <= img.width() / 2 + half; ++x, ++n) {
            const double g = img.rgb("beauty", x, y).g;
            sum += g;
            squares += g * g;
        }
    return float(std::sqrt(std::max(0.0, squares / n - (sum / n) * (sum / n))));
}
}  // namespace

// A glossy metal under an emitter filling its view: every pixel shows the emitter's radiance
// times the lobe's directional albedo (by the eval integral), in the direct layer, with the
// filter and without; glossy_roughness 0 leaves the lobe to the rasterizer (black: no light).
TEST_F(Hybrid, GlossyMetalReflectsTheEmitterByItsAlbedo) {
    const Material m = roughMetal(0.25f);
    const pt::Bsdf up(m, m.albedo, glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), true);
    const float albedo = hemisphereIntegral(up, 2000).g;
    for (const int radius : {0, 3}) {
        const Image img = render(glossyFloor(0.25f, radius, 50.0f, "[2, 1, 0.5]"), "hybrid", 16);
        const glm::vec3 c = centre(img, 4);
        EXPECT_NEAR(c.r, 2.0f * albedo, 0.02f * albedo) << radius;
        EXPECT_NEAR(c.b, 0.5f * albedo, 0.005f * albedo) << radius;
        EXPECT_NEAR(img.rgb("indirect", 16, 16).g, 0.0f, 1e-6f) << radius;
    }
    Scene off = glossyFloor(0.25f, 3, 50.0f, "[2, 1, 0.5]");
    off.gi.set("hybrid.glossy_roughness", "0");
    EXPECT_FALSE(planFrame(off, "hybrid", 1).runs("hybrid.trace"));
    EXPECT_NEAR(centre(render(off, "hybrid", 1), 4).g, 0.0f, 1e-6f);
}

// A small emitter makes one ray a pixel noisy: the edge-aware filter lowers one frame's spread
// across a flat glossy floor and keeps its mean (64 frames, with and without).
TEST_F(Hybrid, FilterSmoothsGlossyNoiseAndKeepsTheMean) {
    auto smallLamp = [](int radius) { return glossyFloor(0.3f, radius, 0.5f, "[20, 20, 20]"); };
    const float raw = centreSpread(render(smallLamp(0), "hybrid", 1), 6);
    const float filtered = centreSpread(render(smallLamp(3), "hybrid", 1), 6);
    EXPECT_GT(raw, 0.0f);
    EXPECT_LT(filtered, 0.5f * raw);
    const float a = centre(render(smallLamp(0), "hybrid", 64), 6).g, b = centre(render(smallLamp(3), "hybrid", 64), 6).g;
    EXPECT_NEAR(b, a, 0.05f * a);
}

// Under a quad light the glossy lobe's highlight stays the rasterized pass's (one point of the
// quad a frame) and the rays leave the quad's geometry alone: neither counted twice nor lost,
// the hybrid gives what the rasterized frame gives over 64 frames.
TEST_F(Hybrid, GlossyLobeUnderAQuadLightMatchesTheRasterizedHighlight) {
    Scene s = lookingDown(R"("metal": {"albedo": [1, 1, 1], "metallic": 1, "roughness": 0.3})",
                          floorOf("metal"),
                          3);
    addQuadLightAbove(s);
    const float rasterized = centre(render(s, "direct", 64), 3).g;
    const float traced = centre(render(s, "hybrid", 64), 3).g;
    EXPECT_GT(rasterized, 0.1f);
    EXPECT_NEAR(traced, rasterized, 0.01f * rasterized);
}

// hybrid.overlap traces the next frame's rays while this frame is lit: the first frame traces its
// own (the image without overlap); later frames show the rays traced from the frame before, the
// same light to a still camera, and one frame late to a moving one. A mirror under a red lamp
// (x < 0) and a blue one (x > 0), seen from above x = -2, then from above x = +2.
TEST_F(Hybrid, OverlappedTracingShowsTheRaysOfTheFrameBefore) {
    Scene s = lookingDown(R"("mirror": {"albedo": [1, 1, 1], "metallic": 1, "roughness": 0},
                             "red": {"albedo": [0, 0, 0], "emission": [1, 0, 0]},
                             "blue": {"albedo": [0, 0, 0], "emission": [0, 0, 1]})",
                          floorOf("mirror") + R"(,
                             {"type": "quad", "name": "red", "material": "red",
                              "corners": [[-50, 3, -50], [0, 3, -50], [0, 3, 50], [-50, 3, 50]]},
                             {"type": "quad", "name": "blue", "material": "blue",
                              "corners": [[0, 3, -50], [50, 3, -50], [50, 3, 50], [0, 3, 50]]})",
                          1);
    auto lookAt = [&s](float x) {
        s.camera.eye = {x, 1.0f, 0.0001f};
        s.camera.target = {x, 0.0f, 0.0f};
    };
    for (bool overlap : {false, true}) {
        s.gi.set("hybrid.overlap", overlap ? "true" : "false");
        lookAt(-2.0f);
        FrameRenderer r(s, FrameOptions{}, planFrame(s, "hybrid", 1));
        r.renderFrame();
        const glm::vec3 first = centre(r.resolve(), 4);
        EXPECT_NEAR(first.r, 1.0f, 0.01f) << overlap;  // traced for this frame either way
        EXPECT_NEAR(first.b, 0.0f, 1e-6f) << overlap;
        lookAt(2.0f);
        r.resetAccumulation();
        r.renderFrame();
        const glm::vec3 moved = centre(r.resolve(), 4);
        // Serial: the blue lamp at once. Overlapped: the red lamp's rays, traced from the last
        // frame's G-buffer, on this frame's pixels.
        EXPECT_NEAR(moved.b, overlap ? 0.0f : 1.0f, 0.01f) << overlap;
        EXPECT_NEAR(moved.r, overlap ? 1.0f : 0.0f, 0.01f) << overlap;
        r.resetAccumulation();
        r.renderFrame();
        const glm::vec3 still = centre(r.resolve(), 4);
        EXPECT_NEAR(still.b, 1.0f, 0.01f) << overlap;
        EXPECT_NEAR(still.r, 0.0f, 1e-6f) << overlap;
    }
}

namespace {

// The beauty layer's largest difference between two images of one size.
float largestDifference(const Image& a, const Image& b) {
    float worst = 0.0f;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const glm::vec3 d = glm::abs(a.rgb("beauty", x, y) - b.rgb("beauty", x, y));
            worst = std::max(worst, std::max(d.r, std::max(d.g, d.b)));
        }
    return worst;
}

}  // namespace

// Each frame uploads only the pixels its rays touch and those the frame before touched: a mirror
// seen at the image's left, then (the camera moved) at its right, leaves nothing at the left,
// and the second frame is the image a renderer that never saw the first makes.
TEST_F(Hybrid, FramesUploadOnlyTheirRaysPixelsAndLeaveNothingOfTheFrameBefore) {
    Scene s = lookingDown(R"("mirror": {"albedo": [1, 1, 1], "metallic": 1, "roughness": 0},
                             "white": {"albedo": [0.5, 0.5, 0.5]},
                             "red": {"albedo": [0, 0, 0], "emission": [1, 0, 0]})",
                          floorOf("white") + R"(,
                             {"type": "quad", "name": "mirror", "material": "mirror",
                              "corners": [[-0.1, 0.001, -0.1], [-0.1, 0.001, 0.1], [0.1, 0.001, 0.1], [0.1, 0.001, -0.1]]},
                             {"type": "quad", "name": "red", "material": "red",
                              "corners": [[-50, 3, -50], [50, 3, -50], [50, 3, 50], [-50, 3, 50]]})",
                          1);
    auto lookAt = [&s](float x) {
        s.camera.eye = {x, 1.0f, 0.0001f};
        s.camera.target = {x, 0.0f, 0.0f};
    };
    lookAt(0.1f);  // the mirror left of the centre
    FrameRenderer moving(s, FrameOptions{}, planFrame(s, "hybrid", 1));
    moving.renderFrame();
    const Image before = moving.resolve();
    lookAt(-0.1f);  // and now right of it
    moving.resetAccumulation();
    moving.renderFrame();
    const Image after = moving.resolve();
    const Image fresh = render(s, "hybrid", 1);
    EXPECT_GT(largestDifference(before, fresh), 0.5f);  // the mirror did move across the image
    EXPECT_EQ(largestDifference(after, fresh), 0.0f);
}
