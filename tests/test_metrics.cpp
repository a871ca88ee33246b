// Image metrics on small hand-made images whose values are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gi/metrics/flip.h"
#include "gi/metrics/image_metrics.h"
#include "scenes/errors.h"
#include "support/test_support.h"

using namespace voxgi;

namespace {

Image uniform(int w, int h, glm::vec3 c, const std::string& layer = "beauty") {
    Image img(w, h);
    ImageLayer& l = img.layer(layer);
    for (std::size_t i = 0; i < img.pixelCount(); ++i)
        for (int k = 0; k < 3; ++k) l.data[3 * i + std::size_t(k)] = c[k];
    return img;
}

std::vector<float> rgbPlane(int w, int h, glm::vec3 c) { return uniform(w, h, c).find("beauty")->data; }

}  // namespace

TEST(Metrics, SquaredAbsoluteAndRelativeErrors) {
    std::vector<float> test{1, 2, 3}, ref{1, 1, 1};
    EXPECT_DOUBLE_EQ(meanSquaredError(test, ref), 5.0 / 3.0);
    EXPECT_DOUBLE_EQ(meanAbsoluteError(test, ref), 1.0);
    EXPECT_NEAR(relativeMse(test, ref), (0.0 + 1.0 + 4.0) / (1.0 + 1e-2) / 3.0, 1e-12);
    // relMSE divides by the reference, not the test: a zero reference leaves only eps.
    EXPECT_NEAR(relativeMse({0.1f}, {0.0f}), 0.01 / 1e-2, 1e-6);
    // Per pixel (here three-channel pixels): the terms summed over channels, whose mean over
    // every value is relMSE.
    const std::vector<float> t6{1, 2, 3, 1, 1, 1}, r6{1, 1, 1, 1, 1, 1};
    const std::vector<double> perPixel = relativeSquaredErrorPerPixel(t6, r6, 3);
    ASSERT_EQ(perPixel.size(), 2u);
    EXPECT_NEAR(perPixel[0], 5.0 / (1.0 + 1e-2), 1e-12);
    EXPECT_EQ(perPixel[1], 0.0);
    EXPECT_NEAR((perPixel[0] + perPixel[1]) / 6.0, relativeMse(t6, r6), 1e-12);
    EXPECT_NEAR(peakSignalToNoise(0.01, 1.0), 20.0, 1e-12);
    EXPECT_NEAR(peakSignalToNoise(0.01, 10.0), 40.0, 1e-12);
    EXPECT_TRUE(std::isinf(peakSignalToNoise(0.0, 1.0)));
}

TEST(Metrics, PearsonCorrelationEq20) {
    EXPECT_NEAR(pearsonCorrelation({1, 2, 3, 4}, {2, 4, 6, 8}), 1.0, 1e-12);
    EXPECT_NEAR(pearsonCorrelation({1, 2, 3, 4}, {8, 6, 4, 2}), -1.0, 1e-12);
    // dx = (-1, 0, 1), dy = (-1, 1, 0): covariance 1/3, variances 2/3 -> 0.5.
    EXPECT_NEAR(pearsonCorrelation({1, 2, 3}, {1, 3, 2}), 0.5, 1e-12);
    EXPECT_TRUE(std::isnan(pearsonCorrelation({1, 1, 1}, {1, 2, 3})));
}

TEST(Metrics, StructuralSimilarity) {
    // Constant images: only the luminance term remains, (2ab + C1) / (a^2 + b^2 + C1).
    std::vector<float> a(8 * 8, 0.2f), b(8 * 8, 0.4f);
    double c1 = 1e-4;
    EXPECT_NEAR(structuralSimilarity(a, b, 8, 8, 1, 1.0), (2 * 0.2 * 0.4 + c1) / (0.04 + 0.16 + c1), 1e-6);
    // Identical textured images: 1. Inverted structure with the same mean and contrast: near -1.
    std::vector<float> checker(16 * 16), inverted(16 * 16);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            checker[std::size_t(y * 16 + x)] = ((x + y) % 2) ? 0.8f : 0.2f;
            inverted[std::size_t(y * 16 + x)] = ((x + y) % 2) ? 0.2f : 0.8f;
        }
    EXPECT_NEAR(structuralSimilarity(checker, checker, 16, 16, 1, 1.0), 1.0, 1e-9);
    EXPECT_LT(structuralSimilarity(checker, inverted, 16, 16, 1, 1.0), -0.9);
}

TEST(Metrics, FlipIsZeroForIdenticalImages) {
    std::vector<float> img(24 * 24 * 3);
    for (std::size_t i = 0; i < img.size(); ++i) img[i] = float((i * 37) % 101) / 100.0f;
    for (float e : flip::ldrFlip(img, img, 24, 24)) ASSERT_NEAR(e, 0.0f, 1e-6f);
    EXPECT_NEAR(flip::hdrFlip(img, img, 24, 24).mean, 0.0, 1e-6);
}

TEST(Metrics, FlipBlackAgainstWhite) {
    // Far from edges the filtered colours are the inputs: L* 0 against 100, no chroma, no
    // features. HyAB = 100, compressed 100^0.7, remapped against the green-blue distance.
    // CIELAB of sRGB green and blue (D65), from the published conversions:
    const double gL = 87.7347, ga = -86.1827, gb = 83.1793, bL = 32.3026, ba = 79.1967, bb = -107.8637;
    auto huntA = [](double L, double a) { return 0.01 * L * a; };
    double cmax = std::pow(std::abs(gL - bL) + std::hypot(huntA(gL, ga) - huntA(bL, ba), huntA(gL, gb) - huntA(bL, bb)), 0.7);
    double dc = std::pow(100.0, 0.7);
    double expected = 0.95 + (dc - 0.4 * cmax) / (cmax - 0.4 * cmax) * 0.05;
    const int n = 48;
    std::vector<float> e = flip::ldrFlip(rgbPlane(n, n, glm::vec3(0.0f)), rgbPlane(n, n, glm::vec3(1.0f)), n, n);
    EXPECT_NEAR(e[std::size_t(n / 2 * n + n / 2)], expected, 2e-3);
    // Smaller differences give smaller errors.
    float small = flip::ldrFlip(rgbPlane(n, n, glm::vec3(0.5f)), rgbPlane(n, n, glm::vec3(0.55f)), n, n)[n * n / 2];
    float large = flip::ldrFlip(rgbPlane(n, n, glm::vec3(0.5f)), rgbPlane(n, n, glm::vec3(0.8f)), n, n)[n * n / 2];
    EXPECT_GT(small, 0.0f);
    EXPECT_LT(small, large);
    EXPECT_LT(large, float(expected));
}

TEST(Metrics, FlipSeesAnEdgeThatIsMissing) {
    // A thin dark line on grey: the test without it has a colour error and a feature error;
    // the feature term raises the error above the colour-only value at the line.
    const int n = 32;
    std::vector<float> ref = rgbPlane(n, n, glm::vec3(0.5f)), test = ref;
    for (int y = 0; y < n; ++y)
        for (int k = 0; k < 3; ++k) ref[3 * std::size_t(y * n + n / 2) + std::size_t(k)] = 0.0f;
    std::vector<float> e = flip::ldrFlip(test, ref, n, n);
    EXPECT_GT(e[std::size_t(n / 2 * n + n / 2)], 0.1f);
    EXPECT_NEAR(e[std::size_t(n / 2 * n + 2)], 0.0f, 0.02f);  // far from the line
}

TEST(Metrics, HdrFlipExposureRange) {
    // ACES maps x85 to 0.85; start puts the brightest luminance there, stop the median.
    std::vector<float> ref;
    for (float v : {1.0f / 16.0f, 1.0f, 16.0f})
        for (int k = 0; k < 3; ++k) ref.push_back(v);
    double start, stop;
    int count;
    flip::exposureRange(ref, start, stop, count);
    double x85 = std::exp2(stop);  // median luminance is 1
    EXPECT_NEAR(flip::acesToneMap(float(x85)), 0.85f, 1e-4f);
    EXPECT_NEAR(start, std::log2(x85 / 16.0), 1e-6);
    EXPECT_NEAR(stop - start, 4.0, 1e-6);
    EXPECT_EQ(count, 4);
    // The median counts black pixels (as NVIDIA's FLIP does): luminances 0, 0, 1, 4, 16 give 1.
    std::vector<float> dark;
    for (float v : {0.0f, 0.0f, 1.0f, 4.0f, 16.0f})
        for (int k = 0; k < 3; ++k) dark.push_back(v);
    flip::exposureRange(dark, start, stop, count);
    EXPECT_NEAR(stop, std::log2(x85), 1e-6);
    // A mostly black reference falls back to the median of its lit pixels (4 of 1, 4, 16).
    dark.insert(dark.begin(), 6, 0.0f);
    flip::exposureRange(dark, start, stop, count);
    EXPECT_NEAR(stop, std::log2(x85 / 4.0), 1e-6);
    EXPECT_EQ(flip::acesToneMap(0.0f), 0.0f);
    EXPECT_LE(flip::acesToneMap(1e6f), 1.0f);
}

TEST(Metrics, ComputeMetricsOnLayers) {
    Image ref = uniform(16, 16, glm::vec3(0.5f));
    Image same = uniform(16, 16, glm::vec3(0.5f));
    ImageMetrics m = computeMetrics(same, ref, "beauty");
    EXPECT_EQ(m.mse, 0.0);
    EXPECT_TRUE(std::isinf(m.psnr));
    EXPECT_NEAR(m.ssim, 1.0, 1e-9);
    EXPECT_NEAR(m.flip, 0.0, 1e-6);
    EXPECT_EQ(m.meanError, 0.0);

    Image brighter = uniform(16, 16, glm::vec3(0.6f));
    m = computeMetrics(brighter, ref, "beauty");
    EXPECT_NEAR(m.rmse, 0.1, 1e-6);
    EXPECT_NEAR(m.mae, 0.1, 1e-6);
    EXPECT_NEAR(m.psnr, 10.0 * std::log10(0.25 / 0.01), 1e-4);
    // Eq. 19 in display units: the difference of the two tone-mapped 8-bit values.
    double expectedMeanError = 255.0 * (toneMapToSrgb(glm::vec3(0.6f), 0.0f).r - toneMapToSrgb(glm::vec3(0.5f), 0.0f).r);
    EXPECT_NEAR(m.meanError, expectedMeanError, 1e-3);
    EXPECT_GT(m.flip, 0.0);
    EXPECT_NE(toJson(m).find("\"relmse_epsilon\": 0.01"), std::string::npos);

    EXPECT_THROW(computeMetrics(same, ref, "indirect"), InputError);
    EXPECT_THROW(computeMetrics(uniform(8, 16, glm::vec3(0.5f)), ref, "beauty"), InputError);
}

TEST(Metrics, OneChannelSsimUsesTheReferenceRange) {
    // Depth from 10 to 25: L is 15 (max - min), not 25 (max - 0).
    const int n = 16;
    Image ref(n, n), test(n, n);
    ImageLayer& r = ref.layer("depth", 1);
    ImageLayer& t = test.layer("depth", 1);
    for (std::size_t i = 0; i < r.data.size(); ++i) {
        r.data[i] = 10.0f + float(i) * 15.0f / float(r.data.size() - 1);
        t.data[i] = r.data[i] + ((i * 7) % 5 == 0 ? 1.5f : -0.5f);
    }
    double ssim = computeMetrics(test, ref, "depth").ssim;
    EXPECT_NEAR(ssim, structuralSimilarity(t.data, r.data, n, n, 1, 15.0), 1e-12);
    EXPECT_GT(std::abs(ssim - structuralSimilarity(t.data, r.data, n, n, 1, 25.0)), 1e-3);
}

TEST(Metrics, CompareCommand) {
    std::string dir = test::makeTempDir("compare");
    Image a = uniform(16, 16, glm::vec3(0.5f)), b = uniform(16, 16, glm::vec3(0.6f));
    b.layer("depth", 1);
    a.layer("depth", 1);
    writeExr(dir + "/a.exr", a);
    writeExr(dir + "/b.exr", b);
    auto r = test::runVoxgi("compare " + dir + "/a.exr " + dir + "/b.exr --diff " + dir + "/d.png --json " + dir + "/m.json");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("RMSE"), std::string::npos);
    EXPECT_TRUE(test::fileExists(dir + "/d.png"));
    EXPECT_TRUE(test::fileExists(dir + "/m.json"));
    // --worst: one bright pixel holds nearly all of relMSE, and is listed first at its place.
    Image spot = uniform(16, 16, glm::vec3(0.6f));
    for (int c = 0; c < 3; ++c) spot.layer("beauty").data[std::size_t(3 * (16 * 5 + 7) + c)] = 60.0f;
    writeExr(dir + "/spot.exr", spot);
    auto worst = test::runVoxgi("compare " + dir + "/spot.exr " + dir + "/b.exr --worst 3");
    ASSERT_EQ(worst.exitCode, 0) << worst.output;
    const std::size_t first = worst.output.find("worst pixels");
    ASSERT_NE(first, std::string::npos) << worst.output;
    EXPECT_NE(worst.output.find("     7    5:", first), std::string::npos) << worst.output;
    EXPECT_NE(worst.output.find("100.0 %", first), std::string::npos) << worst.output;
    EXPECT_EQ(test::runVoxgi("compare " + dir + "/a.exr " + dir + "/b.exr --worst -1").exitCode, 2);
    auto depth = test::runVoxgi("compare " + dir + "/a.exr " + dir + "/b.exr --aov depth");
    EXPECT_EQ(depth.exitCode, 0) << depth.output;
    auto missing = test::runVoxgi("compare " + dir + "/a.exr " + dir + "/nothere.exr");
    EXPECT_EQ(missing.exitCode, 2) << missing.output;
    auto layer = test::runVoxgi("compare " + dir + "/a.exr " + dir + "/b.exr --aov normal --json " + dir + "/x.json");
    EXPECT_EQ(layer.exitCode, 2) << layer.output;
    EXPECT_FALSE(test::fileExists(dir + "/x.json"));
    // NaN or infinity in either image: refused, not NaN metrics with exit 0.
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        Image c = uniform(16, 16, glm::vec3(0.5f));
        c.layer("beauty").data[7] = bad;
        writeExr(dir + "/c.exr", c);
        auto r2 = test::runVoxgi("compare " + dir + "/c.exr " + dir + "/b.exr --json " + dir + "/y.json");
        EXPECT_EQ(r2.exitCode, 2) << r2.output;
        EXPECT_NE(r2.output.find("c.exr: layer beauty holds 1 NaN or infinite values"), std::string::npos) << r2.output;
        EXPECT_FALSE(test::fileExists(dir + "/y.json"));
    }
}
