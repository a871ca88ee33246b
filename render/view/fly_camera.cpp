#include "render/view/fly_camera.h"

#include <algorithm>
#include <cmath>

namespace voxgi::view {

namespace {
constexpr float kMaxPitch = 1.5533430f;  // 89 degrees: never look straight along `up`
}

FlyCamera::FlyCamera(const Camera& camera) : eye_(camera.eye), up_(glm::normalize(camera.up)) {
    glm::vec3 dir = camera.target - camera.eye;
    dir = glm::length(dir) > 0.0f ? glm::normalize(dir) : -up_;
    glm::vec3 horizontal = dir - glm::dot(dir, up_) * up_;
    if (glm::length(horizontal) < 1e-6f) {
        // Looking straight up or down: any horizontal reference works.
        horizontal = std::abs(up_.x) < 0.9f ? glm::cross(up_, glm::vec3(1, 0, 0)) : glm::cross(up_, glm::vec3(0, 0, 1));
    }
    reference_ = glm::normalize(horizontal);
    pitch_ = std::clamp(std::asin(std::clamp(glm::dot(dir, up_), -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
}

glm::vec3 FlyCamera::forward() const {
    glm::vec3 side = glm::cross(reference_, up_);
    glm::vec3 horizontal = std::cos(yaw_) * reference_ + std::sin(yaw_) * side;
    return glm::normalize(std::cos(pitch_) * horizontal + std::sin(pitch_) * up_);
}

glm::vec3 FlyCamera::right() const { return glm::normalize(glm::cross(forward(), up_)); }

bool FlyCamera::move(const MoveInput& input, float speed, float seconds) {
    glm::vec3 delta = (input.forward * forward() + input.right * right() + input.up * up_) * (speed * seconds);
    if (delta == glm::vec3(0.0f)) return false;
    eye_ += delta;
    return true;
}

bool FlyCamera::turn(float yawRadians, float pitchRadians) {
    float pitch = std::clamp(pitch_ + pitchRadians, -kMaxPitch, kMaxPitch);
    if (yawRadians == 0.0f && pitch == pitch_) return false;
    yaw_ += yawRadians;
    pitch_ = pitch;
    return true;
}

void FlyCamera::applyTo(Camera& camera) const {
    camera.eye = eye_;
    camera.target = eye_ + forward();
    camera.up = up_;
}

}  // namespace voxgi::view
