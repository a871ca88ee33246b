// The passes a technique runs in a frame for a given scene, decided before anything runs (so
// `voxgi render --plan` needs no GL): each pass is also the name of its timer stage, and the
// technique runs a pass only when its plan lists it.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace voxgi {

struct PlannedPass {
    std::string name;    // the timer stage, "<section>.<pass>"
    std::string reason;  // why it runs (or, in `skipped`, why not)
};

struct TechniquePlan {
    std::vector<PlannedPass> update;   // run by GiTechnique::update, in order (before direct light)
    std::vector<PlannedPass> apply;    // run by GiTechnique::applyIndirect (after direct light)
    std::vector<PlannedPass> skipped;  // passes the method has that this scene does not need
    std::vector<std::string> notes;    // when the passes repeat, what they reuse
    // For screen-space techniques that gather light from the surfaces on screen: the frame draws
    // this fraction of the picture's width and height beyond each edge as well (G-buffer, direct
    // light, the technique's passes; the camera's field widened to match, so the picture's pixels
    // are the same), and the picture is cropped from it. 0: none.
    float guardBand = 0.0f;

    bool runs(const std::string& pass) const {
        for (const auto* list : {&update, &apply})
            for (const PlannedPass& p : *list)
                if (p.name == pass) return true;
        return false;
    }
    // An update pass that runs when `needed`, else is listed as skipped with `skipReason`.
    void updateIf(bool needed, std::string pass, std::string reason, std::string skipReason) {
        if (needed) update.push_back({std::move(pass), std::move(reason)});
        else skipped.push_back({std::move(pass), std::move(skipReason)});
    }
};

}  // namespace voxgi
