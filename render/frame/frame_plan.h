// The passes a frame runs for a scene and a method, and only those (ARCHITECTURE: "leave out
// what a scene does not need"). FrameRenderer runs exactly this plan, and `voxgi render --plan`
// prints the same object. Every pass is also the name of its timer stage.
#pragma once

#include <string>
#include <vector>

#include "gi/technique_plan.h"
#include "scenes/scene.h"

namespace voxgi {

struct FramePlan {
    std::string method;
    int frames = 1;
    std::vector<PlannedPass> passes;   // in the order they run, the method's included
    std::vector<PlannedPass> skipped;  // passes left out, with why
    std::vector<std::string> notes;
    TechniquePlan technique;           // the method's own passes

    bool runs(const std::string& pass) const;
    std::string describe() const;
};

// InputError / NotImplementedError for a bad method or setting, like createTechnique. No GL.
FramePlan planFrame(const Scene& scene, const std::string& method, int frames);

}  // namespace voxgi
