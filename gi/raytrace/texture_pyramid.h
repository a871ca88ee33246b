// Mip pyramids of the scene's albedo textures for rays that stand for a cone of directions
// (DDGI probe rays each carry 4 pi / N sr): the albedo is averaged over the cone's footprint by
// picking the level from the ray cone's width at the hit (Akenine-Moller et al., "Texture Level
// of Detail Strategies for Real-Time Ray Tracing", Ray Tracing Gems, 2019) instead of point
// sampling the full-resolution image. Besides removing texture aliasing from the probes, coarse
// levels stay in cache where random texels of the full image miss it.
#pragma once

#include <cstdint>
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
    // Bilinear lookup in the level nearest to `lod`, linear RGB; `lod` is clamped to the
    // pyramid, so lod < 0.5 is exactly Texture::sampleLinear.
    glm::vec3 sample(glm::vec2 uv, float lod) const;
    // 0.5 log2(texels of level 0): turns a triangle's uv density into its texel density here.
    float log2Texels() const { return log2Texels_; }
    // Mean linear colour of one level.
    glm::vec3 levelMean(int level) const;

private:
    struct Level {
        int width = 0, height = 0;
        const std::uint8_t* rgba = nullptr;
    };
    std::vector<Level> levels_;
    std::vector<std::vector<std::uint8_t>> storage_;  // levels 1...
    float log2Texels_ = 0.0f;
};

// The level-of-detail of a ray cone at a triangle hit: log2 of the cone's width over the
// texel size there. `texelDensity` is the triangle's constant (0.5 log2 of its texel area over
// its world area, texels counted at level 0), `coneWidth` the cone's width at the hit and
// `cosine` |n . d| between the triangle's normal and the ray.
float rayConeLod(float texelDensity, float coneWidth, float cosine);

// 0.5 log2(texel area / world area) of a triangle with corners p0..p2 and uvs t0..t2 on a
// width x height texture; -inf for a zero uv area, +inf for a zero world area.
float triangleTexelDensity(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec2 t0, glm::vec2 t1, glm::vec2 t2,
                           int width, int height);

// The apex angle (radians) of the cone that holds 1 / rays of the sphere: a probe ray's share.
float coneSpreadForRays(int rays);

}  // namespace voxgi
