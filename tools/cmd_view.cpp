// voxgi view: the interactive viewer (render/view/viewer.h). With --frames N it renders N
// frames and closes, which with --screenshot makes it scriptable for tests and captures.
#include <cstdio>

#include "gi/methods.h"
#include "render/view/viewer.h"
#include "scenes/errors.h"
#include "tools/commands.h"
#include "tools/display_args.h"
#include "tools/method_help.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi view SCENE [--method NAME] [--width W --height H] [--window WxH] [--exposure auto|STOPS] [--tonemap filmic|reinhard]\n"
    "       [--frames N --screenshot SHOT.png] [--script CAMERA.json] [--out-dir DIR] [--no-panel]\n"
    "       [--capture-window WINDOW.png] [--backend cpu|gl]\n"
    "       [--set section.key=value]...\n"
    "  opens a window (needs a display; without one use `voxgi render`). Controls: docs/viewer.md\n"
    "  --frames N: render N frames then close; --screenshot writes SHOT.png and SHOT.exr at the end;\n"
    "  --capture-window: PNG of what the window shows on the last frame (panel included)" VOXGI_DISPLAY_USAGE;

int runView(const std::vector<std::string>& argv) {
    Args args(argv, {"--method", "--width", "--height", "--window", "--exposure", "--tonemap", "--frames", "--screenshot", "--script",
                     "--out-dir", "--set", "--backend", "--capture-window"},
              {"--no-panel"}, {"--set"});
    args.requirePositional(1, kUsage);
    if (!view::displayAvailable()) {
        std::fprintf(stderr, "voxgi view: no display (DISPLAY is not set); for images without a display use "
                             "`voxgi render SCENE -o out.exr --png out.png`\n");
        return kFailure;
    }
    view::ViewerOptions options;
    options.frames = args.integer("--frames", 0, 1, 1 << 20);
    const DisplayArgs display = displayArguments(args);
    options.autoExposure = display.autoExposure;
    options.exposure = display.exposureStops;
    options.toneCurve = display.toneCurve;
    options.panel = !args.flag("--no-panel");
    if (auto shot = args.value("--screenshot")) {
        requireWritable(*shot, "--screenshot");
        options.screenshot = *shot;
    }
    options.script = args.value("--script", "");
    if (auto capture = args.value("--capture-window")) {
        requireWritable(*capture, "--capture-window");
        options.windowCapture = *capture;
    }
    options.outputDir = args.value("--out-dir", ".");
    if (auto window = args.value("--window")) {
        if (std::sscanf(window->c_str(), "%dx%d", &options.windowWidth, &options.windowHeight) != 2 ||
            options.windowWidth < 64 || options.windowHeight < 64 || options.windowWidth > 16384 ||
            options.windowHeight > 16384)
            throw InputError("--window " + *window + ": expected WxH, e.g. 1280x720 (64..16384)");
    }

    Scene scene = loadSceneArgument(args.positional()[0]);
    applySceneOverrides(args, scene);
    options.method = methodArgument(args, scene, "direct");
    validateMethod(options.method, scene);
    return view::runViewer(scene, options);
}

}  // namespace

VOXGI_REGISTER_COMMAND_WITH_DETAILS("view", kUsage, runView, methodList);

}  // namespace voxgi::cli
