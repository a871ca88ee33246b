// The passes a scene needs, and only those (ARCHITECTURE: "leave out what a scene does not
// need"). `voxgi render --plan` prints it.
#pragma once

#include <string>
#include <vector>

#include "scenes/scene.h"

namespace voxgi {

struct PlannedPass {
    std::string name;
    std::string reason;
};

struct FramePlan {
    std::string method;
    int frames = 1;
    std::vector<PlannedPass> passes;
    std::vector<PlannedPass> skipped;  // passes left out, with why
    std::string describe() const;
};

FramePlan planFrame(const Scene& scene, const std::string& method, int frames);

}  // namespace voxgi
