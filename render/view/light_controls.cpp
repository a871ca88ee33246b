#include "render/view/light_controls.h"

#include <cmath>

namespace voxgi::view {

void moveLight(Light& light, glm::vec3 offset, float sceneRadius) {
    if (light.type == LightType::Directional) {
        glm::vec3 d = light.direction + offset / sceneRadius;
        if (glm::length(d) > 1e-6f) light.direction = glm::normalize(d);
        return;
    }
    light.position += offset;
}

LightAnimator::LightAnimator(const std::vector<Light>& rest, glm::vec3 up, float sceneRadius, float period)
    : rest_(rest), up_(glm::normalize(up)), radius_(0.15f * sceneRadius), period_(period) {
    a_ = glm::normalize(std::abs(up_.x) < 0.9f ? glm::cross(up_, glm::vec3(1, 0, 0)) : glm::cross(up_, glm::vec3(0, 0, 1)));
    b_ = glm::cross(up_, a_);
}

void LightAnimator::apply(double seconds, std::vector<Light>& lights) const {
    const double twoPi = 6.283185307179586;
    for (std::size_t i = 0; i < lights.size() && i < rest_.size(); ++i) {
        double phase = twoPi * (seconds / double(period_) + double(i) / double(rest_.size()));
        glm::vec3 circle = float(std::cos(phase)) * a_ + float(std::sin(phase)) * b_;
        Light moved = rest_[i];
        if (moved.type == LightType::Directional) {
            // A sun swings by about 0.3 rad instead of translating (translation changes nothing).
            moved.direction = glm::normalize(rest_[i].direction + 0.3f * circle);
        } else {
            moved.position = rest_[i].position + radius_ * circle;
        }
        lights[i] = moved;
    }
}

}  // namespace voxgi::view
