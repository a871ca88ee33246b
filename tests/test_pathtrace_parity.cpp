// Units cross-check between the two renderers: the rasterizer's `direct` layer (shadow maps,
// the quad light as jittered point samples) against the path tracer with --max-bounces 1 on the
// Cornell box. Both claim physical radiance, so they must agree up to shadow-map error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gi/pathtrace/path_tracer.h"
#include "render/frame/frame_renderer.h"
#include "render/gl/context.h"
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
