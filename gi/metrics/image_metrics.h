// Image error metrics between a test image and a reference (the path-traced one), for
// `voxgi compare` and `voxgi eval`. Definitions, with their constants, in docs/reference.md.
#pragma once

#include <string>
#include <vector>

#include "scenes/image.h"

namespace voxgi {

constexpr double kRelMseEpsilon = 1e-2;  // relMSE = mean (x - y)^2 / (y^2 + eps)

struct ImageMetrics {
    std::string layer;
    int channels = 0;
    std::size_t pixels = 0;
    // On linear values, every channel of every pixel pooled.
    double mse = 0.0;
    double rmse = 0.0;
    double relMse = 0.0;
    double mae = 0.0;
    double psnr = 0.0;         // dB against the reference's peak value; +inf for identical images
    // On display values (ACES + sRGB at exposure 0, as the PNG previews) for RGB layers,
    // linear values for 1-channel layers.
    double ssim = 0.0;
    double meanError = 0.0;    // seed 003 Eq. 19, in 8-bit display units (0..255) for RGB layers
    double pearson = 0.0;      // seed 003 Eq. 20 on the same values; NaN when either is constant
    // HDR-FLIP (Andersson et al. 2021) mean over pixels, RGB layers only (NaN otherwise).
    double flip = 0.0;
};

// Throws InputError when the layer is missing from either image or the sizes differ.
ImageMetrics computeMetrics(const Image& test, const Image& reference, const std::string& layer);
// The metrics as one JSON object.
std::string toJson(const ImageMetrics& metrics);

// The building blocks, on interleaved values of equal length (tested on hand-made images).
double meanSquaredError(const std::vector<float>& test, const std::vector<float>& reference);
double relativeMse(const std::vector<float>& test, const std::vector<float>& reference, double epsilon = kRelMseEpsilon);
// relMSE's terms summed per pixel (their mean over pixels / channels is relativeMse): which
// pixels the error comes from.
std::vector<double> relativeSquaredErrorPerPixel(const std::vector<float>& test, const std::vector<float>& reference,
                                                 int channels, double epsilon = kRelMseEpsilon);
double meanAbsoluteError(const std::vector<float>& test, const std::vector<float>& reference);
double peakSignalToNoise(double mse, double peak);
// Population Pearson product-moment correlation of the pooled values (seed 003 Eq. 20).
double pearsonCorrelation(const std::vector<float>& test, const std::vector<float>& reference);
// Structural similarity (Wang et al. 2004): 11x11 Gaussian window (sigma 1.5), C1 = (0.01 L)^2,
// C2 = (0.03 L)^2, edges clamped, mean over pixels and channels.
double structuralSimilarity(const std::vector<float>& test, const std::vector<float>& reference, int width,
                            int height, int channels, double dynamicRange);

}  // namespace voxgi
