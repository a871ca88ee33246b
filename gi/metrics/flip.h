// FLIP, the perceptual error of Andersson et al. ("FLIP: A Difference Evaluator for
// Alternating Images", HPG 2020) and its HDR extension ("Visualizing Errors in Rendered High
// Dynamic Range Images", Eurographics 2021), written from the papers' descriptions.
#pragma once

#include <vector>

namespace voxgi::flip {

struct Options {
    double pixelsPerDegree = 67.0;  // 0.7 m from a 0.7 m wide 4K monitor, the papers' default
};

// LDR-FLIP of two images of linear RGB values in [0, 1] (3 floats per pixel, rows first):
// the per-pixel error in [0, 1].
std::vector<float> ldrFlip(const std::vector<float>& test, const std::vector<float>& reference, int width,
                           int height, const Options& options = {});

struct HdrResult {
    std::vector<float> error;  // per pixel, the maximum over the exposures
    double mean = 0.0;
    double startExposure = 0.0;  // stops
    double stopExposure = 0.0;
    int exposures = 0;
};

// HDR-FLIP of two linear HDR RGB images: LDR-FLIP after ACES tone mapping at exposures spread
// from where the reference's brightest pixel maps to 0.85 to where its median luminance does.
HdrResult hdrFlip(const std::vector<float>& test, const std::vector<float>& reference, int width, int height,
                  const Options& options = {});

// The tone curve HDR-FLIP uses (ACES fit, Narkowicz 2015, with 0.6 pre-exposure), and the
// exposure range it derives from a reference image.
float acesToneMap(float x);
void exposureRange(const std::vector<float>& reference, double& start, double& stop, int& count);

}  // namespace voxgi::flip
