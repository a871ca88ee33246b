#include "tools/display_args.h"

#include <cstdlib>

#include "scenes/errors.h"

namespace voxgi::cli {

DisplayArgs displayArguments(const Args& args) {
    DisplayArgs d;
    const std::string exposure = args.value("--exposure", "auto");
    if (exposure != "auto") {
        d.autoExposure = false;
        d.exposureStops = float(args.number("--exposure", 0.0, -30.0, 30.0));
    }
    const std::string curve = args.value("--tonemap", "filmic");
    d.toneCurve = toneCurveFromName(curve);
    if (d.toneCurve < 0) throw InputError("--tonemap " + curve + ": expected filmic or reinhard");
    return d;
}

Image::Display resolveDisplay(const DisplayArgs& display, const Image& image) {
    Image::Display out;
    out.set = true;
    out.exposureStops = display.autoExposure ? autoExposureStops(image, "beauty") : display.exposureStops;
    out.toneCurve = display.toneCurve;
    return out;
}

}  // namespace voxgi::cli
