#include "gi/isr/isr_reference.h"

#include <cmath>

#include "gi/isr/isr_passes.h"
#include "gl/resources.h"
#include "shaders/shared/disc_samples.h"
#include "shaders/shared/isr.h"

namespace voxgi {

std::vector<glm::vec4> readIsrTexture(const IsrPasses& passes, unsigned texture) {
    const glm::ivec2 s = passes.coarseSize();
    const std::vector<float> f = gl::readTexture(texture, s.x, s.y, 4);
    std::vector<glm::vec4> out(std::size_t(s.x) * std::size_t(s.y));
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = {f[4 * i], f[4 * i + 1], f[4 * i + 2], f[4 * i + 3]};
    return out;
}

IsrCoarseBuffers readIsrCoarse(const IsrPasses& passes) {
    IsrCoarseBuffers c;
    c.width = passes.coarseSize().x;
    c.height = passes.coarseSize().y;
    c.position = readIsrTexture(passes, passes.position());
    c.normal = readIsrTexture(passes, passes.normal());
    c.radiance = readIsrTexture(passes, passes.radiance());
    return c;
}

std::vector<glm::vec4> isrGatherCpu(const IsrCoarseBuffers& c, int patches, float radiusPixels, int frame, bool discs) {
    std::vector<glm::vec4> out(std::size_t(c.width) * std::size_t(c.height), glm::vec4(0.0f));
    const float weight = shading::kPi * radiusPixels * radiusPixels / float(patches);
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
            const glm::ivec2 pixel(x, y);
            const glm::vec4 p = c.at(c.position, pixel);
            if (p.w <= 0.0f) continue;
            const glm::vec3 n = glm::vec3(c.at(c.normal, pixel));
            const float rotation = shading::discRotation(pixel, frame);
            glm::vec4 sum(0.0f);
            for (int i = 0; i < patches; ++i) {
                const glm::ivec2 q = pixel + glm::ivec2(glm::round(radiusPixels * shading::vogelDisc(i, patches, rotation)));
                if (q == pixel || q.x < 0 || q.y < 0 || q.x >= c.width || q.y >= c.height) continue;
                const glm::vec4 xp = c.at(c.position, q);
                if (xp.w <= 0.0f) continue;
                const glm::vec4 radiance = c.at(c.radiance, q);
                sum += shading::isrPatchContribution(glm::vec3(p), n, glm::vec3(xp), glm::vec3(c.at(c.normal, q)), radiance.w,
                                                     glm::vec3(radiance), discs);
            }
            out[std::size_t(y) * std::size_t(c.width) + std::size_t(x)] = sum * weight;
        }
    return out;
}

glm::vec4 isrUpsampleCpu(const IsrCoarseBuffers& c, const std::vector<glm::vec4>& values, int factor, glm::ivec2 pixel,
                         float depth, glm::vec3 normal) {
    const glm::vec2 g = (glm::vec2(pixel) + 0.5f) / float(factor) - 0.5f;
    const glm::ivec2 base(glm::floor(g));
    const glm::vec2 f = g - glm::vec2(base);
    glm::vec4 sum(0.0f), nearest(0.0f);
    float weights = 0.0f, nearestGap = 1e30f;
    for (int k = 0; k < 4; ++k) {
        const glm::ivec2 o(k & 1, k >> 1);
        const glm::ivec2 q = glm::clamp(base + o, glm::ivec2(0), glm::ivec2(c.width - 1, c.height - 1));
        const glm::vec4 coarse = c.at(c.normal, q);
        if (coarse.w <= 0.0f) continue;
        const glm::vec4 value = c.at(values, q);
        const glm::vec2 b = glm::mix(glm::vec2(1.0f) - f, f, glm::vec2(o));
        const float w = shading::isrUpsampleWeight(b.x * b.y, depth, coarse.w, normal, glm::vec3(coarse));
        sum += w * value;
        weights += w;
        if (std::abs(coarse.w - depth) < nearestGap) {
            nearestGap = std::abs(coarse.w - depth);
            nearest = value;
        }
    }
    return weights > 1e-6f ? sum / weights : nearest;
}

}  // namespace voxgi
