// `voxgi view`: the interactive window. Renders with FrameRenderer and a GI technique, shows the
// tone-mapped frame or an AOV, an ImGui panel (timings, method, settings, debug views), and
// takes WASD + mouse-look, light dragging, screenshots, .vdb dumps and shader reloads.
#pragma once

#include <string>

#include "scenes/scene.h"

namespace voxgi::view {

struct ViewerOptions {
    std::string method = "direct";
    int frames = 0;            // > 0: render exactly this many frames, then close (tests, capture)
    std::string screenshot;    // written when the viewer closes: PATH (.png) and PATH's .exr
    std::string script;        // camera path JSON (view_script.h)
    std::string windowCapture; // PNG of the last frame's window contents (panel included)
    std::string outputDir = ".";  // where the screenshot and dump keys write
    float exposure = 0.0f;     // stops, when not autoExposure
    bool autoExposure = true;  // the shown layer's log-average luminance, adapted over time
    int toneCurve = 0;         // shading::kToneFilmic or kToneReinhard
    int windowWidth = 0;       // 0: the render size, at least 1280 x 720
    int windowHeight = 0;
    bool panel = true;
};

// True when a window system is reachable ($DISPLAY or $WAYLAND_DISPLAY set).
bool displayAvailable();

// Runs until the window closes (or `frames` frames); returns the process exit code. Throws
// InputError / gl::GlError like the other verbs. `scene` is modified (camera, lights).
int runViewer(Scene& scene, const ViewerOptions& options);

}  // namespace voxgi::view
