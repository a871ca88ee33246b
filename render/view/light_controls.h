// Moving lights in the viewer: dragging the main light and a looping animation of every
// light, so a method's response to dynamic light (lag, flicker) can be watched.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi::view {

// Moves a point, spot or quad light by `offset` (world units); a directional light instead
// tilts its direction by offset / sceneRadius radians (about), staying normalized.
void moveLight(Light& light, glm::vec3 offset, float sceneRadius);

// Each light circles its rest position (radius 15% of the scene radius, one turn per
// `period` seconds, phases spread over the lights) about the scene's up axis.
class LightAnimator {
public:
    LightAnimator(const std::vector<Light>& rest, glm::vec3 up, float sceneRadius, float period = 6.0f);
    void apply(double seconds, std::vector<Light>& lights) const;
    void setRest(const std::vector<Light>& rest) { rest_ = rest; }

private:
    std::vector<Light> rest_;
    glm::vec3 up_, a_, b_;
    float radius_, period_;
};

}  // namespace voxgi::view
