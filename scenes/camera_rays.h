// The primary rays of a pinhole camera for an image of a given size: the path tracer's rays,
// and the reconstruction of a pixel's surface point from the depth it stored.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi {

struct CameraRays {
    glm::vec3 eye{0.0f}, forward{0.0f, 0.0f, -1.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 1.0f, 0.0f};
    float tanHalfY = 1.0f, aspect = 1.0f;

    CameraRays(const Camera& c, int width, int height)
        : eye(c.eye),
          forward(glm::normalize(c.target - c.eye)),
          right(glm::normalize(glm::cross(forward, c.up))),
          up(glm::cross(right, forward)),
          tanHalfY(std::tan(glm::radians(c.fovYDegrees) * 0.5f)),
          aspect(float(width) / float(height)) {}

    // The (unnormalized) direction through image point (sx, sy) in [0, 1]^2, y down.
    glm::vec3 direction(float sx, float sy) const {
        return forward + (2.0f * sx - 1.0f) * tanHalfY * aspect * right + (1.0f - 2.0f * sy) * tanHalfY * up;
    }
};

}  // namespace voxgi
