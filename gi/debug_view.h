// What a technique shows of its state in the viewer (Capsaicin's technique debug views): each
// view is declared once with its name, key and options (the viewer builds its GUI from them) and
// drawn by the technique as plain geometry, boxes and spheres, that the viewer's overlay renders.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gi/settings_table.h"
#include "scenes/scene.h"

namespace voxgi {

struct DebugBox {
    glm::vec3 min, max, color;
};

struct DebugSphere {
    glm::vec4 centerRadius;
    glm::vec4 r, g, b;  // a constant colour in .x, or 2-band SH coefficients per channel
};

struct DebugDrawing {
    std::vector<DebugBox> boxes;
    std::vector<DebugSphere> spheres;
    bool shSpheres = false;  // spheres carry SH, painted toward each point's normal
    float shScale = 1.0f;    // SH spheres: multiplier before the exposure and tone curve
};

struct DebugViewInfo {
    std::string name;    // `show NAME` in view scripts
    std::string label;   // in the viewer panel
    char key = 0;        // the viewer's toggle key ('A'..'Z'), 0 for none
    std::string doc;
    // Options as settings of the section "<name>", e.g. "lpv_cells.cascade"; a script sets them
    // with `show NAME:option=value,...`.
    std::vector<SettingInfo> options;
    int refreshFrames = 1;  // redrawn every this many frames (a read-back is costly)
};

// What a technique needs to draw a view besides its own state.
struct DebugViewContext {
    Camera camera;
    float exposureStops = 0.0f;
    const GiSettings& options;  // the view's options (defaults for keys not set)
};

// The bounds of a method's volumes (light volumes, probe volumes), one view name and key for
// every method that has volumes; `doc` says what the boxes are.
constexpr const char* kCascadeBoundsView = "cascades";
DebugViewInfo cascadeBoundsView(std::string doc);
// The colour of cascade i of `count` in the bounds view: finest orange to coarsest cyan.
glm::vec3 cascadeColor(int i, int count);

}  // namespace voxgi
