// State shared by the viewer's loop and its panel (internal to render/view).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gi/debug_view.h"
#include "render/frame/frame_renderer.h"
#include "render/view/display_pass.h"
#include "render/view/debug_overlay.h"
#include "render/view/fly_camera.h"
#include "render/view/light_controls.h"
#include "render/view/viewer.h"

struct GLFWwindow;

namespace voxgi::view {

struct PointerState {
    double x = 0, y = 0;
    bool tracking = false;  // a look or drag button was down at the last poll
};

// A debug view that methods declare (gi/debug_view.h), as the viewer keeps it.
struct MethodView {
    bool on = false;
    GiSettings options;       // its option values ("<view>.<option>"); the rest are defaults
    DebugDrawing drawing;     // the technique's last drawing of it
    int drawnFrame = -1000;   // the frame it was drawn; far in the past forces a redraw
};

struct ViewerState {
    Scene& scene;
    ViewerOptions options;
    std::unique_ptr<FrameRenderer> renderer;
    std::unique_ptr<DisplayPass> display;
    std::unique_ptr<DebugOverlay> overlay;
    FlyCamera camera;
    LightAnimator animator;
    float sceneRadius = 1.0f;

    std::string method;
    DisplayMode mode = DisplayMode::Beauty;
    DebugViews debug;
    float speed = 1.0f;        // world units per second
    float exposure = 0.0f;     // stops: what the window and screenshots show
    bool autoExposure = true;  // exposure follows the picture (eye adaptation, docs/display.md)
    bool exposureMeasured = false;  // auto exposure has a first value (no adaptation from 0)
    int toneCurve = 0;
    bool animateLights = false;
    double animationTime = 0.0;
    bool showPanel = true;
    int frame = 0;
    double frameMs = 0.0;

    // Requests from keys or the panel, served between frames.
    bool rebuildTechnique = false;
    bool reloadShaders = false;
    bool takeScreenshot = false;
    bool dumpVdb = false;
    bool viewChanged = false;
    std::string status;        // last message (file written, error)
    std::map<std::string, std::size_t> timerCounts;  // samples per stage at the previous panel
    std::map<std::string, MethodView> methodViews;   // by view name, kept across method switches
    PointerState pointer;
    int screenshotCount = 0;

    ViewerState(Scene& s, const ViewerOptions& o);
};

// ImGui panel; edits the state (requests are served by the loop).
void drawPanel(ViewerState& state);
// Key and scroll callbacks (the window's user pointer becomes `state`); ImGui chains to them.
void installInputCallbacks(GLFWwindow* window, ViewerState& state);
// Per frame: WASD/QE movement, right-button look, Ctrl+left-button light drag.
void handleInput(GLFWwindow* window, ViewerState& state, float seconds);
// One key press (GLFW key code and modifier bits), as docs/viewer.md lists them; Esc is the
// window's business. Requests are served by the loop.
void handleKey(ViewerState& state, int glfwKey, int mods);
// A display mode or debug view by name (script "show" events), a method's view with options as
// NAME:option=value,...; InputError when unknown.
void applyShow(ViewerState& state, const std::string& name);
// Toggles the current method's debug view bound to `key` ('A'..'Z'); false when none is.
bool toggleMethodView(ViewerState& state, char key);
// The viewer's own letter keys (movement, actions, its views), which a method's view may not use.
extern const char* const kViewerKeys;

}  // namespace voxgi::view
