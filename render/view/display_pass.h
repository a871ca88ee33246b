// Draws the frame renderer's accumulation (or one AOV) into the window, tone-mapped like
// writePng, scaled to the window with the aspect ratio kept (letterboxed).
#pragma once

#include "render/frame/frame_renderer.h"
#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi::view {

enum class DisplayMode { Beauty = 0, Direct, Indirect, Albedo, Normal };
const char* displayModeName(DisplayMode mode);
constexpr int kDisplayModeCount = 5;

class DisplayPass {
public:
    DisplayPass();  // compiles shaders/view/display.frag; call again to reload
    void draw(FrameRenderer& renderer, DisplayMode mode, float exposureStops, int windowWidth, int windowHeight);

private:
    gl::Program program_;
    gl::Handle vao_;
};

}  // namespace voxgi::view
