// --exposure auto|STOPS and --tonemap filmic|reinhard, shared by render, reference and view:
// how an HDR image is shown (shaders/shared/tone_map.h, docs/display.md).
#pragma once

#include "scenes/image.h"
#include "tools/args.h"

namespace voxgi::cli {

struct DisplayArgs {
    bool autoExposure = true;  // from the image's log-average luminance (autoExposureStops)
    float exposureStops = 0.0f;
    int toneCurve = 0;         // shading::kToneFilmic or kToneReinhard
};

// The usage lines of both options, for a command's usage text (a literal, so they concatenate).
#define VOXGI_DISPLAY_USAGE                                                                              \
    "\n  --exposure: stops, or auto (default): the beauty layer's log-average luminance to middle grey" \
    "\n  --tonemap: filmic (default, ACES fit) or reinhard; the EXR header records both (docs/display.md)"
DisplayArgs displayArguments(const Args& args);
// The display `image` gets: the auto exposure of its beauty layer, or the fixed one.
Image::Display resolveDisplay(const DisplayArgs& display, const Image& image);

}  // namespace voxgi::cli
