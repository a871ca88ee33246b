// voxgi render: the real-time path, headless. Renders N frames with a GI method, writes the
// averaged HDR image (EXR with AOV layers), an optional PNG preview and per-stage timings.
#include <chrono>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "gi/technique.h"
#include "gl/context.h"
#include "render/frame/frame_plan.h"
#include "render/frame/frame_renderer.h"
#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "scenes/image.h"
#include "tools/commands.h"
#include "tools/display_args.h"
#include "tools/method_help.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi render SCENE [--method NAME] -o OUT.exr [--png OUT.png] [--width W --height H] [--frames N]\n"
    "       [--timings T.json] [--exposure auto|STOPS] [--tonemap filmic|reinhard] [--backend cpu|gl] [--set section.key=value]... [--plan]\n"
    "  SCENE: a scene .json, a mesh file, or a built-in scene name (cornell-box)\n"
    "  --frames: frames accumulated (default 64 with area lights, else 1)" VOXGI_DISPLAY_USAGE;

int runRender(const std::vector<std::string>& argv) {
    Args args(argv, {"--method", "-o", "--png", "--width", "--height", "--frames", "--timings", "--exposure", "--tonemap", "--set", "--backend"},
              {"--plan"}, {"--set"});
    args.requirePositional(1, kUsage);
    auto out = args.value("-o");
    if (!out && !args.flag("--plan")) throw InputError("-o OUT.exr is required; usage: " + usageLine(kUsage));
    requireOutputs(args, {"-o", "--png", "--timings"});
    const DisplayArgs display = displayArguments(args);

    Scene scene = loadSceneArgument(args.positional()[0]);
    applySceneOverrides(args, scene);
    // --method, else the scene's gi.method, else direct light only.
    const std::string method = methodArgument(args, scene, "direct");
    const int frames = args.integer("--frames", defaultFrameCount(scene), 1, 1 << 20);
    // Printed and then run: the renderer runs exactly these passes.
    FramePlan plan = planFrame(scene, method, frames);
    if (args.flag("--plan")) {
        std::printf("%s", plan.describe().c_str());
        if (!out) return kOk;
    }

    auto start = std::chrono::steady_clock::now();
    auto context = gl::Context::createHeadless();
    FrameRenderer renderer(scene, FrameOptions{}, plan);
    for (int f = 0; f < frames; ++f) renderer.renderFrame();
    Image image = renderer.resolve();
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    image.display = resolveDisplay(display, image);
    writeExr(*out, image);
    if (auto png = args.value("--png"))
        writePng(*png, image, "beauty", image.display.exposureStops, image.display.toneCurve);
    if (auto t = args.value("--timings")) {
        // Per-stage times, and what the technique reports about its last frame (steps taken,
        // rays traced...) under "technique".
        auto json = nlohmann::ordered_json::parse(renderer.timers().toJson());
        if (const GiTechnique* technique = renderer.technique()) {
            nlohmann::ordered_json stats = nlohmann::ordered_json::object();
            for (const TechniqueStat& st : technique->stats()) stats[st.name] = {{"value", st.value}, {"unit", st.unit}};
            json["technique"] = stats;
        }
        writeTextAtomically(*t, json.dump(2) + "\n");
    }
    std::printf("rendered %s with %s: %dx%d, %d frame(s) in %.2f s on %s\n", args.positional()[0].c_str(),
                method.c_str(), renderer.width(), renderer.height(), frames, seconds, context->description().c_str());
    std::printf("wrote %s%s%s\n", out->c_str(), args.has("--png") ? (" and " + *args.value("--png")).c_str() : "",
                args.has("--timings") ? (" and " + *args.value("--timings")).c_str() : "");
    return kOk;
}

}  // namespace

VOXGI_REGISTER_COMMAND_WITH_DETAILS("render", kUsage, runRender, methodListWithSettings);

}  // namespace voxgi::cli
