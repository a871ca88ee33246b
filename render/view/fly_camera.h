// First-person camera for the viewer: yaw/pitch about the scene camera's up axis, WASD moves
// along the view direction in world units per second. Pure math, no GL, so it is testable.
#pragma once

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi::view {

struct MoveInput {
    float forward = 0.0f;  // -1..1 (S..W)
    float right = 0.0f;    // -1..1 (A..D)
    float up = 0.0f;       // -1..1 (Q..E)
};

class FlyCamera {
public:
    // Starts where `camera` looks (eye and target); `up` stays the scene camera's up.
    explicit FlyCamera(const Camera& camera);

    // Moves by speed * seconds along the view basis; true when the eye changed.
    bool move(const MoveInput& input, float speed, float seconds);
    // Turns by yaw/pitch in radians (positive: right and up); pitch stays inside +-89 degrees.
    bool turn(float yawRadians, float pitchRadians);

    glm::vec3 eye() const { return eye_; }
    glm::vec3 forward() const;
    glm::vec3 right() const;
    // Writes eye, target (one unit ahead) and up into the scene camera; size and lens untouched.
    void applyTo(Camera& camera) const;

private:
    glm::vec3 eye_;
    glm::vec3 up_;
    glm::vec3 reference_;  // horizontal direction with yaw 0
    float yaw_ = 0.0f;
    float pitch_ = 0.0f;
};

}  // namespace voxgi::view
