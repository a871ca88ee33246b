// Convergence of the path tracer on the Cornell box: RMSE against a long render falls as
// spp^-0.5 (log-log slope -0.5 +- 0.1), the signature of an unbiased Monte Carlo estimate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gi/metrics/image_metrics.h"
#include "gi/pathtrace/path_tracer.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {
constexpr int kSize = 32;
// Pixels that see the light (radiance 17) or touch one that does: partial coverage gives a few
// edge pixels a variance a thousand times the walls', and left in they make the RMSE of a
// 32x32 image a noisy estimate of itself. The walls still carry every bounce of light.
std::vector<float> withoutLight(const std::vector<float>& values, const std::vector<float>& reference) {
    auto bright = [&](int x, int y) {
        x = std::clamp(x, 0, kSize - 1);
        y = std::clamp(y, 0, kSize - 1);
        return reference[3 * std::size_t(y * kSize + x)] > 2.0f;
    };
    std::vector<float> out;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            bool near = false;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) near = near || bright(x + dx, y + dy);
            if (near) continue;
            for (int c = 0; c < 3; ++c) out.push_back(values[3 * std::size_t(y * kSize + x) + std::size_t(c)]);
        }
    return out;
}
}  // namespace

TEST(PathTracerConvergence, CornellRmseFallsAsInverseSquareRootOfSamples) {
    Scene s = test::cornellBox();
    PathTracerOptions o;
    o.width = o.height = kSize;
    o.seed = 1000;
    PathTracer reference(s, o);
    reference.render(8192);
    const Image referenceImage = reference.image();
    const std::vector<float>& ref = referenceImage.find("beauty")->data;

    o.seed = 1;
    PathTracer tracer(s, o);
    std::vector<double> logSpp, logRmse;
    for (int spp : {4, 16, 64, 256}) {
        tracer.render(spp - tracer.samplesPerPixel());
        double rmse = std::sqrt(meanSquaredError(withoutLight(tracer.image().find("beauty")->data, ref), withoutLight(ref, ref)));
        std::printf("spp %3d: RMSE %.5f\n", spp, rmse);
        logSpp.push_back(std::log(double(spp)));
        logRmse.push_back(std::log(rmse));
    }
    // Least-squares slope of log RMSE against log spp.
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < logSpp.size(); ++i) {
        mx += logSpp[i] / double(logSpp.size());
        my += logRmse[i] / double(logSpp.size());
    }
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < logSpp.size(); ++i) {
        sxy += (logSpp[i] - mx) * (logRmse[i] - my);
        sxx += (logSpp[i] - mx) * (logSpp[i] - mx);
    }
    double slope = sxy / sxx;
    std::printf("log-log slope %.3f (expected -0.5)\n", slope);
    EXPECT_NEAR(slope, -0.5, 0.1);
}
