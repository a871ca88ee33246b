// A G-buffer built on the CPU, for tests and benchmarks that drive a technique's apply pass
// without the frame renderer: four RGBA32F textures in the frame renderer's layout (see
// GBufferView) and a cleared RGBA32F target, bound as the draw framebuffer with its viewport.
#pragma once

#include <vector>

#include "gi/technique.h"
#include "gl/resources.h"

namespace voxgi {

struct UploadedGBuffer {
    gl::Handle position, normal, albedo, emission, target, framebuffer;
    GBufferView view;

    // The target's pixels, RGBA, bottom row first (GL order).
    std::vector<float> readTarget() const;
    // New contents for the same size, and the target cleared (a G-buffer refilled every frame).
    // Only `region` (x, y, width, height) is uploaded when given: the caller knows the texels
    // outside it are the same as before.
    void refill(const std::vector<glm::vec4>& position, const std::vector<glm::vec4>& normal,
                const std::vector<glm::vec4>& albedo, const std::vector<glm::vec4>& emission);
    void refill(const std::vector<glm::vec4>& position, const std::vector<glm::vec4>& normal,
                const std::vector<glm::vec4>& albedo, const std::vector<glm::vec4>& emission, glm::ivec4 region);
};

// Uploads the texels of `region` (x, y, width, height; nothing when empty) of `data`, an image
// `width` texels wide, into the same texels of an RGBA32F texture.
void uploadRegion(GLuint texture, int width, glm::ivec4 region, const std::vector<glm::vec4>& data);

// The smallest rectangle holding both (x, y, width, height; one with no area holds nothing).
glm::ivec4 boundingRegion(glm::ivec4 a, glm::ivec4 b);

UploadedGBuffer uploadGBuffer(const std::vector<glm::vec4>& position, const std::vector<glm::vec4>& normal,
                              const std::vector<glm::vec4>& albedo, const std::vector<glm::vec4>& emission,
                              int width, int height, glm::vec3 eye);

}  // namespace voxgi
