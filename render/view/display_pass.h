// Draws the frame renderer's accumulation (or one AOV) into the window, tone-mapped like
// writePng (shaders/shared/tone_map.h), scaled to the window with the aspect ratio kept
// (letterboxed); measures the exposure that auto exposure aims for.
#pragma once

#include <optional>

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
    void draw(FrameRenderer& renderer, DisplayMode mode, float exposureStops, int toneCurve, int windowWidth,
              int windowHeight);
    // The exposure (stops) that maps the log-average luminance of the shown layer's lit pixels
    // (a 64 x 64 grid of them) to middle grey, as autoExposureStops does for an image; nullopt
    // when no pixel is lit or the mode shows no radiance (albedo, normal).
    std::optional<float> autoExposureStops(FrameRenderer& renderer, DisplayMode mode);

private:
    gl::Program program_, logLuminance_;
    gl::Handle result_;
    gl::Handle vao_;
};

}  // namespace voxgi::view
