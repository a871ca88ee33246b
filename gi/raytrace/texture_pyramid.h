// Mip pyramids of the scene's albedo textures for rays that stand for a cone of directions
// (DDGI probe rays each carry 4 pi / N sr): the albedo is averaged over the cone's footprint by
// picking the level from the ray cone's width at the hit (Akenine-Moller et al., "Texture Level
// of Detail Strategies for Real-Time Ray Tracing", Ray Tracing Gems, 2019) instead of point
// sampling the full-resolution image. Besides removing texture aliasing from the probes, coarse
// levels stay in cache where random texels of the full image miss it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include <glm/glm.hpp>

namespace voxgi {

struct Texture;

class TexturePyramid {
public:
    // Level 0 is the texture itself (borrowed: it must outlive the pyramid); each further level
    // halves both sides (rounding down, at least 1) with a box filter in linear space.
    explicit TexturePyramid(const Texture& texture);

    int levels() const { return int(levels_.size()); }
    int width(int level) const { return levels_[std::size_t(level)].width; }
    int height(int level) const { return levels_[std::size_t(level)].height; }
    // The level whose texels are nearest in size to a footprint `texels` level-0 texels wide:
    // round(log2(texels)) clamped to the pyramid, read off the float's exponent (no log).
    int levelForFootprint(float texels) const {
        // round(log2 x) = floor(log2(x sqrt 2)), the exponent of x sqrt 2 once that is >= 1.
        const float x = texels * 1.41421356f;
        if (!(x >= 2.0f)) return 0;  // also NaN
        const int top = std::max(int(levels_.size()) - 1, 0);
        if (!(x < 3.0e38f)) return top;
        std::uint32_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        return std::min(int(bits >> 23) - 127, top);
    }
    // Linear RGB from `level` (clamped to the pyramid): bilinear in level 0, which is exactly
    // Texture::sampleLinear, and the nearest texel above it (the level itself is the filter:
    // one of its texels spans the footprint, and probes average over rays anyway).
    glm::vec3 sample(glm::vec2 uv, int level) const {
        if (levels_.empty()) return glm::vec3(1.0f);
        level = std::clamp(level, 0, int(levels_.size()) - 1);
        const Level& l = levels_[std::size_t(level)];
        if (level == 0) return sampleLevelZero(uv);
        const float u = uv.x - std::floor(uv.x), v = 1.0f - (uv.y - std::floor(uv.y));
        const int x = std::max(std::min(int(u * float(l.width)), l.width - 1), 0);
        const int y = std::max(std::min(int(v * float(l.height)), l.height - 1), 0);
        const std::uint8_t* p = &l.rgba[(std::size_t(y) * std::size_t(l.width) + std::size_t(x)) * 4];
        return glm::vec3(decode_[p[0]], decode_[p[1]], decode_[p[2]]);
    }
    // sqrt(texels of level 0): turns a triangle's uv scale into its texel scale here.
    float texelScale() const { return texelScale_; }
    // Mean linear colour of one level.
    glm::vec3 levelMean(int level) const;

private:
    struct Level {
        int width = 0, height = 0;
        const std::uint8_t* rgba = nullptr;
    };
    glm::vec3 sampleLevelZero(glm::vec2 uv) const;

    std::vector<Level> levels_;
    const float* decode_ = nullptr;  // sRGB code -> linear
    std::vector<std::vector<std::uint8_t>> storage_;  // levels 1...
    float texelScale_ = 0.0f;
};

// The width, in texels, of a ray cone's footprint on a triangle: `texelScale` is the
// triangle's texels per unit length (triangleTexelScale), `coneWidth` the cone's width at the
// hit and `cosine` |n . d| between the triangle's normal and the ray (the footprint stretches
// as the ray grazes).
float rayConeFootprint(float texelScale, float coneWidth, float cosine);

// sqrt(texel area / world area) of a triangle with corners p0..p2 and uvs t0..t2 on a
// width x height texture: texels per unit length; 0 for a zero uv area, inf for a zero world area.
float triangleTexelScale(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec2 t0, glm::vec2 t1, glm::vec2 t2,
                         int width, int height);

// The apex angle (radians) of the cone that holds 1 / rays of the sphere: a probe ray's share.
float coneSpreadForRays(int rays);

}  // namespace voxgi
