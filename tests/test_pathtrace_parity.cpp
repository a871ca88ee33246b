// Units cross-check between the two renderers: the rasterizer's `direct` layer (shadow maps,
// the quad light as jittered point samples) against the path tracer with --max-bounces 1 on the
// Cornell box. Both claim physical radiance, so they must agree up to shadow-map error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gi/pathtrace/path_tracer.h"
#include "render/frame/frame_renderer.h"
#include "gl/context.h"
#include "scenes/scene_loader.h"
#include "support/test_support.h"

using namespace voxgi;

TEST(PathTracerParity, DirectLayerMatchesRasterizer) {
    auto context = gl::Context::createHeadless();
    Scene s = test::cornellBox();
    s.camera.width = s.camera.height = 64;

    FrameRenderer raster(s, FrameOptions{});
    for (int i = 0; i < 256; ++i) raster.renderFrame();
    Image rasterImage = raster.resolve();

    PathTracerOptions o;
    o.maxBounces = 1;
    PathTracer tracer(s, o);
    tracer.render(256);
    Image traced = tracer.image();
    // One bounce: nothing indirect.
    for (float v : traced.find("indirect")->data) ASSERT_EQ(v, 0.0f);

    const auto& a = rasterImage.find("direct")->data;
    const auto& b = traced.find("direct")->data;
    ASSERT_EQ(a.size(), b.size());
    // Totals per channel (the light's power reaching the image) and the mean per-pixel
    // difference relative to the mean, both away from the light itself, whose edge pixels
    // (radiance 17 against 0.5) dominate any sum.
    glm::dvec3 sumA(0.0), sumB(0.0);
    double absDiff = 0.0;
    for (std::size_t p = 0; p < a.size() / 3; ++p) {
        glm::dvec3 ca(a[3 * p], a[3 * p + 1], a[3 * p + 2]), cb(b[3 * p], b[3 * p + 1], b[3 * p + 2]);
        if (std::max(ca.r, cb.r) > 5.0) continue;
        sumA += ca;
        sumB += cb;
        absDiff += std::abs(ca.r - cb.r) + std::abs(ca.g - cb.g) + std::abs(ca.b - cb.b);
    }
    glm::dvec3 rel = (sumA - sumB) / sumB;
    double meanRelDiff = absDiff / (sumB.r + sumB.g + sumB.b);
    std::printf("direct layer, rasterizer vs path tracer (B = 1): totals differ by %+.2f%% %+.2f%% %+.2f%% (RGB); "
                "mean per-pixel |difference| / mean = %.2f%%\n",
                100 * rel.r, 100 * rel.g, 100 * rel.b, 100 * meanRelDiff);
    for (int c = 0; c < 3; ++c) EXPECT_LT(std::abs(rel[c]), 0.02) << "channel " << c;
    EXPECT_LT(meanRelDiff, 0.10);
}

TEST(PathTracerParity, GlossyPlaneUnderPointLightMatchesRasterizer) {
    // The same BRDF in GLSL and C++: a glossy, partly metallic plane under a point light seen at
    // a grazing angle (a highlight in view). Nothing occludes, so both are noise-free up to the
    // path tracer's pixel jitter.
    auto context = gl::Context::createHeadless();
    Scene s = parseSceneJson(R"({
      "camera": {"eye": [0, 1.2, 2.5], "target": [0, 0, -0.5], "fov": 50, "resolution": [64, 64]},
      "materials": {"m": {"albedo": [0.8, 0.5, 0.2], "roughness": 0.35, "metallic": 0.5, "specular": 0.5}},
      "lights": [{"type": "point", "position": [0.2, 1.0, -1.5], "intensity": 5}],
      "meshes": [{"type": "quad", "material": "m", "corners": [[-4,0,4],[4,0,4],[4,0,-4],[-4,0,-4]]}]})",
                             "glossy.json");
    FrameRenderer raster(s, FrameOptions{});
    for (int i = 0; i < 16; ++i) raster.renderFrame();
    Image a = raster.resolve();
    PathTracerOptions o;
    o.maxBounces = 1;
    PathTracer tracer(s, o);
    tracer.render(16);
    Image b = tracer.image();
    const auto& da = a.find("direct")->data;
    const auto& db = b.find("direct")->data;
    glm::dvec3 sumA(0.0), sumB(0.0);
    double absDiff = 0.0;
    float peak = 0.0f;
    for (std::size_t p = 0; p < da.size() / 3; ++p) {
        glm::dvec3 ca(da[3 * p], da[3 * p + 1], da[3 * p + 2]), cb(db[3 * p], db[3 * p + 1], db[3 * p + 2]);
        sumA += ca;
        sumB += cb;
        absDiff += std::abs(ca.r - cb.r) + std::abs(ca.g - cb.g) + std::abs(ca.b - cb.b);
        peak = std::max(peak, db[3 * p]);
    }
    glm::dvec3 rel = (sumA - sumB) / sumB;
    double meanRelDiff = absDiff / (sumB.r + sumB.g + sumB.b);
    std::printf("glossy plane, rasterizer vs path tracer: totals differ by %+.2f%% %+.2f%% %+.2f%%; mean |difference| / "
                "mean = %.2f%%, highlight peak %.3f\n",
                100 * rel.r, 100 * rel.g, 100 * rel.b, 100 * meanRelDiff, peak);
    for (int c = 0; c < 3; ++c) EXPECT_LT(std::abs(rel[c]), 0.01) << "channel " << c;
    EXPECT_LT(meanRelDiff, 0.03);
}
