#include "gi/pathtrace/environment.h"

#include <algorithm>
#include <cmath>

#include "shaders/shared/color.h"
#include "shaders/shared/sky.h"

namespace voxgi::pt {

EnvironmentSampler::EnvironmentSampler(const Sky& sky) {
    if (!sky.enabled || !sky.tabulated()) return;
    width_ = sky.width;
    height_ = sky.height;
    const std::size_t w = std::size_t(width_), h = std::size_t(height_);
    std::vector<double> weight(w * h), rowSum(h, 0.0);
    double total = 0.0;
    for (std::size_t y = 0; y < h; ++y) {
        // The texel's solid angle is proportional to the sine at its centre row.
        const double s = std::sin((double(y) + 0.5) * shading::kPiDouble / double(h));
        for (std::size_t x = 0; x < w; ++x) {
            const double v = std::max(double(shading::luminanceRec709(sky.table[y * w + x])), 0.0) * s;
            weight[y * w + x] = v;
            rowSum[y] += v;
        }
        total += rowSum[y];
    }
    if (!(total > 0.0) || !std::isfinite(total)) {
        width_ = height_ = 0;
        return;
    }
    rowCdf_.resize(h);
    columnCdf_.resize(w * h);
    texelProbability_.resize(w * h);
    double running = 0.0;
    for (std::size_t y = 0; y < h; ++y) {
        running += rowSum[y];
        rowCdf_[y] = float(running / total);
        double column = 0.0;
        for (std::size_t x = 0; x < w; ++x) {
            column += weight[y * w + x];
            // A dark row is never picked; its columns stay uniform so the table is well formed.
            columnCdf_[y * w + x] = rowSum[y] > 0.0 ? float(column / rowSum[y]) : float(double(x + 1) / double(w));
            texelProbability_[y * w + x] = float(weight[y * w + x] / total);
        }
        columnCdf_[y * w + w - 1] = 1.0f;
    }
    rowCdf_.back() = 1.0f;
}

EnvironmentSampler::Sample EnvironmentSampler::sample(glm::vec2 u) const {
    Sample out;
    if (!active()) return out;
    const std::size_t w = std::size_t(width_);
    // Row, then column, each by its cumulative sums; u is reused within the chosen interval.
    const std::size_t y = std::min(std::size_t(std::upper_bound(rowCdf_.begin(), rowCdf_.end(), u.y) - rowCdf_.begin()),
                                   std::size_t(height_ - 1));
    const float rowLow = y == 0 ? 0.0f : rowCdf_[y - 1], rowSpan = rowCdf_[y] - rowLow;
    const float fy = rowSpan > 0.0f ? std::clamp((u.y - rowLow) / rowSpan, 0.0f, 0.99999994f) : 0.5f;
    const float* row = columnCdf_.data() + y * w;
    const std::size_t x = std::min(std::size_t(std::upper_bound(row, row + w, u.x) - row), w - 1);
    const float colLow = x == 0 ? 0.0f : row[x - 1], colSpan = row[x] - colLow;
    const float fx = colSpan > 0.0f ? std::clamp((u.x - colLow) / colSpan, 0.0f, 0.99999994f) : 0.5f;
    const glm::vec2 uv((float(x) + fx) / float(width_), (float(y) + fy) / float(height_));
    out.direction = shading::skyDirection(uv);
    const float sinTheta = std::sin(shading::kPi * uv.y);
    const float p = texelProbability_[y * w + x];
    if (!(sinTheta > 0.0f) || !(p > 0.0f)) return Sample{};
    // Density in (u, v) is p * width * height; d(omega) = 2 pi^2 sin(theta) du dv.
    out.pdf = p * float(width_) * float(height_) / (2.0f * shading::kPi * shading::kPi * sinTheta);
    return out;
}

float EnvironmentSampler::pdf(glm::vec3 towardSky) const {
    if (!active()) return 0.0f;
    const glm::vec2 uv = shading::skyUv(towardSky);
    const int x = std::min(int(uv.x * float(width_)), width_ - 1), y = std::min(int(uv.y * float(height_)), height_ - 1);
    const float sinTheta = std::sin(shading::kPi * uv.y);
    if (!(sinTheta > 0.0f)) return 0.0f;
    return texelProbability_[std::size_t(y) * std::size_t(width_) + std::size_t(x)] * float(width_) * float(height_) /
           (2.0f * shading::kPi * shading::kPi * sinTheta);
}

}  // namespace voxgi::pt
