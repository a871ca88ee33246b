// Image-space radiosity on the CPU: the gather and the upsample of shaders/isr/ over coarse
// buffers read back from the GPU, the reference the GPU passes are checked against
// (tests/test_isr.cpp). The per-patch math is shaders/shared/isr.h, compiled by both.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace voxgi {

class IsrPasses;

struct IsrCoarseBuffers {
    int width = 0, height = 0;
    std::vector<glm::vec4> position, normal, radiance;  // as IsrPasses keeps them

    glm::vec4 at(const std::vector<glm::vec4>& layer, glm::ivec2 p) const {
        return layer[std::size_t(p.y) * std::size_t(width) + std::size_t(p.x)];
    }
};

// The passes' coarse buffers, read back (needs the GL context they live in).
IsrCoarseBuffers readIsrCoarse(const IsrPasses& passes);
// A coarse texture of the passes (RGBA32F, coarseSize()), read back.
std::vector<glm::vec4> readIsrTexture(const IsrPasses& passes, unsigned texture);

// The gather of shaders/isr/gather.comp for every coarse pixel: rgb irradiance, w occlusion by
// spheres (or by discs, as with a far field).
std::vector<glm::vec4> isrGatherCpu(const IsrCoarseBuffers& c, int patches, float radiusPixels, int frame, bool discs = false);

// The upsample of shaders/isr/apply.comp at full-resolution pixel `pixel` (depth along the
// camera's axis `depth`, normal `normal`) from coarse values `values` (coarse size as `c`).
glm::vec4 isrUpsampleCpu(const IsrCoarseBuffers& c, const std::vector<glm::vec4>& values, int factor, glm::ivec2 pixel,
                         float depth, glm::vec3 normal);

}  // namespace voxgi
