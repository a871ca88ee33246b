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
    void refill(const std::vector<glm::vec4>& position, const std::vector<glm::vec4>& normal,
                const std::vector<glm::vec4>& albedo, const std::vector<glm::vec4>& emission);
};

UploadedGBuffer uploadGBuffer(const std::vector<glm::vec4>& position, const std::vector<glm::vec4>& normal,
                              const std::vector<glm::vec4>& albedo, const std::vector<glm::vec4>& emission,
                              int width, int height, glm::vec3 eye);

}  // namespace voxgi
