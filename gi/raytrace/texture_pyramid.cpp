#include "gi/raytrace/texture_pyramid.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "scenes/scene.h"

namespace voxgi {

TexturePyramid::TexturePyramid(const Texture& texture) : decode_(srgbDecodeTable()) {
    if (texture.width <= 0 || texture.height <= 0 ||
        texture.rgba.size() < std::size_t(texture.width) * std::size_t(texture.height) * 4)
        return;
    levels_.push_back({texture.width, texture.height, texture.rgba.data()});
    texelScale_ = std::sqrt(float(texture.width) * float(texture.height));
    while (levels_.back().width > 1 || levels_.back().height > 1) {
        const Level& src = levels_.back();
        Level dst;
        dst.width = std::max(src.width / 2, 1);
        dst.height = std::max(src.height / 2, 1);
        std::vector<std::uint8_t> data(std::size_t(dst.width) * std::size_t(dst.height) * 4);
        // Each destination texel averages the source texels it covers: 2x2, or 3 along an
        // odd side's last texel so none is dropped; alpha is averaged as stored.
        for (int y = 0; y < dst.height; ++y) {
            const int y0 = 2 * y, y1 = std::min(y == dst.height - 1 ? src.height : 2 * y + 2, src.height);
            for (int x = 0; x < dst.width; ++x) {
                const int x0 = 2 * x, x1 = std::min(x == dst.width - 1 ? src.width : 2 * x + 2, src.width);
                glm::vec4 sum(0.0f);
                for (int j = y0; j < std::max(y1, y0 + 1); ++j)
                    for (int i = x0; i < std::max(x1, x0 + 1); ++i) {
                        const std::uint8_t* p = &src.rgba[(std::size_t(j) * std::size_t(src.width) + std::size_t(i)) * 4];
                        sum += glm::vec4(srgbToLinear(p[0]), srgbToLinear(p[1]), srgbToLinear(p[2]), float(p[3]));
                    }
                const float n = float((std::max(y1, y0 + 1) - y0) * (std::max(x1, x0 + 1) - x0));
                std::uint8_t* q = &data[(std::size_t(y) * std::size_t(dst.width) + std::size_t(x)) * 4];
                for (int c = 0; c < 3; ++c) q[c] = linearToSrgb(sum[c] / n);
                q[3] = std::uint8_t(std::lround(sum[3] / n));
            }
        }
        storage_.push_back(std::move(data));
        dst.rgba = storage_.back().data();
        levels_.push_back(dst);
    }
}

glm::vec3 TexturePyramid::sampleLevelZero(glm::vec2 uv) const {
    const Level& l = levels_.front();
    return sampleSrgbBilinear(l.rgba, l.width, l.height, uv);
}

glm::vec3 TexturePyramid::levelMean(int level) const {
    const Level& l = levels_[std::size_t(level)];
    glm::dvec3 sum(0.0);
    for (std::size_t i = 0; i < std::size_t(l.width) * std::size_t(l.height); ++i)
        for (int c = 0; c < 3; ++c) sum[c] += srgbToLinear(l.rgba[4 * i + std::size_t(c)]);
    return glm::vec3(sum / double(std::size_t(l.width) * std::size_t(l.height)));
}

float rayConeFootprint(float texelScale, float coneWidth, float cosine) {
    return texelScale * std::abs(coneWidth) / std::abs(cosine);
}

float triangleTexelScale(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec2 t0, glm::vec2 t1, glm::vec2 t2,
                         int width, int height) {
    glm::vec2 a = t1 - t0, b = t2 - t0;
    float texels = std::abs(a.x * b.y - a.y * b.x) * float(width) * float(height);
    float world = glm::length(glm::cross(p1 - p0, p2 - p0));
    return std::sqrt(texels / world);
}

float coneSpreadForRays(int rays) {
    // A cone of apex angle g holds 2 pi (1 - cos(g / 2)) sr; set that to 4 pi / rays.
    float c = 1.0f - 2.0f / float(std::max(rays, 1));
    return 2.0f * std::acos(std::clamp(c, -1.0f, 1.0f));
}

}  // namespace voxgi
