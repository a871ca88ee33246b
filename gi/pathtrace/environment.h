// Next-event estimation of a tabulated sky (atmosphere or environment map): directions drawn
// in proportion to each texel's luminance times its solid angle (a piecewise-constant density
// over the equirectangular map, rows by their marginal sums, then a column within the row),
// weighted by MIS against BSDF sampling. A constant sky is left to BSDF sampling alone.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi::pt {

class EnvironmentSampler {
public:
    explicit EnvironmentSampler(const Sky& sky);

    bool active() const { return !rowCdf_.empty(); }
    // A direction toward the sky from u in [0, 1)^2; pdf per steradian (0: nothing sampled).
    struct Sample {
        glm::vec3 direction{0.0f};
        float pdf = 0.0f;
    };
    Sample sample(glm::vec2 u) const;
    // The pdf (per steradian) of sample() returning unit direction `towardSky`.
    float pdf(glm::vec3 towardSky) const;

private:
    int width_ = 0, height_ = 0;
    std::vector<float> rowCdf_;     // height_ entries, the last 1
    std::vector<float> columnCdf_;  // per row, width_ entries, the last 1
    std::vector<float> texelProbability_;
};

}  // namespace voxgi::pt
