// voxgi eval: error against run time. Renders scenes with methods x quality presets, measures
// each image against a (cached) path-traced reference on the full image and the indirect layer,
// and writes report.md / report.json / results.csv with plots, FLIP maps and crops. With
// --stability it runs the stiff and extreme cases instead (eval_stability.cpp).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "gi/methods.h"
#include "gl/context.h"
#include "render/frame/frame_renderer.h"
#include "scenes/errors.h"
#include "tools/commands.h"
#include "tools/eval_report.h"
#include "tools/eval_stability.h"
#include "tools/eval_views.h"
#include "render/view/view_sampler.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi eval SCENE... -o DIR [--methods NAME,...] [--presets low,medium,high]\n"
    "       [--reference REF.exr | auto] [--spp N] [--cache DIR] [--frames N] [--warmup N] [--converge EPS]\n"
    "       [--max-warmup N] [--width W --height H] [--set section.key=value]...\n"
    "       [--views N | --views VIEWS.json] [--view-seed S] [--no-caustics]\n"
    "  voxgi eval --stability -o DIR [--cases NAME,...]\n"
    "  --methods: default every built method; --presets: each method's (voxgi methods NAME), one run for a method with none\n"
    "  --spp: reference samples per pixel (default 256); --cache: reference cache (default DIR/cache)\n"
    "  --frames: frames accumulated per run (default the scene's, at least warm-up + 5); --warmup: untimed frames (4)\n"
    "  --converge: methods whose light builds up over frames (ddgi) warm up until it changes less than this\n"
    "    relative amount over their window (0.002), or for --max-warmup frames (300)\n"
    "  --views: judge over N camera views drawn in the scene's free space (seed --view-seed, default 1), or over\n"
    "    the camera keys of a viewer script; each view has its own cached reference; writes views.md/json/csv\n"
    "  --no-caustics: path-traced references without caustics (voxgi reference --no-caustics)";

std::string sceneName(const std::string& argument) {
    std::string stem = std::filesystem::path(argument).stem().string();
    for (char& c : stem)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    return stem.empty() ? "scene" : stem;
}

// The centre half of each image, side by side, tone-mapped as the previews.
void writeCrops(const std::string& path, const std::vector<const Image*>& images) {
    const Image& first = *images.front();
    const int w = std::max(1, first.width() / 2), h = std::max(1, first.height() / 2);
    const int x0 = (first.width() - w) / 2, y0 = (first.height() - h) / 2;
    const int gap = 4, total = int(images.size()) * (w + gap) - gap;
    std::vector<std::uint8_t> rgb(std::size_t(3) * std::size_t(total) * std::size_t(h), 255);
    for (std::size_t n = 0; n < images.size(); ++n)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                glm::vec3 c = toneMapToSrgb(images[n]->rgb("beauty", x0 + x, y0 + y), 0.0f);
                std::size_t o = 3 * (std::size_t(y) * std::size_t(total) + n * std::size_t(w + gap) + std::size_t(x));
                for (int k = 0; k < 3; ++k) rgb[o + std::size_t(k)] = std::uint8_t(std::lround(255.0f * std::clamp(c[k], 0.0f, 1.0f)));
            }
    writePngRgb8(path, total, h, rgb);
}

void makeOutputFolder(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) throw InputError("-o " + dir + ": cannot create the folder");
}

// The method's presets among `wanted`, in the order asked; a method without presets runs once
// with its defaults ("default").
std::vector<Preset> presetsFor(const MethodInfo& method, const std::vector<std::string>& wanted) {
    if (method.presets.empty()) return {{"default", {}}};
    std::vector<Preset> out;
    for (const std::string& w : wanted)
        for (const Preset& p : method.presets)
            if (p.name == w) out.push_back(p);
    return out;
}

// Every name in `wanted` is some method's preset.
void requireKnownPresets(const std::vector<std::string>& wanted) {
    std::string known;
    for (const std::string& w : wanted) {
        bool found = false;
        for (const MethodInfo& m : methods())
            for (const Preset& p : m.presets) {
                found = found || p.name == w;
                if (known.find(p.name) == std::string::npos) known += (known.empty() ? "" : ", ") + p.name;
            }
        if (!found) throw InputError("--presets " + w + ": unknown preset (known: " + known + ")");
    }
}

EvalRow measure(const std::string& method, const Preset& preset, MethodRun run, const Reference& ref, const std::string& dir,
                const std::string& sceneDir) {
    EvalRow row;
    row.method = method;
    row.preset = preset.name;
    row.settings = settingsText(preset.settings);
    row.frameMs = run.frameMs;
    row.warmupFrames = run.warmupFrames;
    row.frames = run.warmupFrames + run.timedFrames;
    row.temporal = run.temporal;
    row.converged = run.converged;
    row.convergeMs = run.convergeMs;
    row.timedFrames = run.timedFrames;
    row.stages = run.stages;
    row.full = computeMetrics(run.image, ref.image, "beauty");
    row.indirect = computeMetrics(run.image, ref.image, "indirect");
    row.meanIndirect = layerMean(run.image, "indirect");
    const std::string stem = preset.name == "default" ? method : method + "-" + preset.name;
    row.imagePng = sceneDir + "/" + stem + ".png";
    row.flipPng = sceneDir + "/" + stem + "-flip.png";
    writePng(dir + "/" + row.imagePng, run.image, "beauty", 0.0f);
    writeFlipMap(dir + "/" + row.flipPng, run.image, ref.image);
    return row;
}

// The frames, warm-up and convergence every run on `scene` gets, from the command line.
RenderSettings renderSettingsFor(const Args& args, const Scene& scene) {
    RenderSettings rs;
    rs.width = scene.camera.width;
    rs.height = scene.camera.height;
    rs.warmup = args.integer("--warmup", 4, 0, 1 << 16);
    rs.frames = args.integer("--frames", std::max(defaultFrameCount(scene), rs.warmup + 5), 1, 1 << 20);
    rs.convergeBelow = args.number("--converge", 0.002, 0.0, 1.0);
    rs.maxWarmup = args.integer("--max-warmup", 300, 0, 1 << 20);
    return rs;
}

// --views: N views drawn in each scene, or the camera keys of a script (one scene). Read with
// the other inputs, before any output exists.
std::vector<std::vector<Camera>> viewsFor(const Args& args, const std::vector<Scene>& scenes) {
    const std::string viewsArg = args.value("--views", "");
    const bool counted = !viewsArg.empty() && std::all_of(viewsArg.begin(), viewsArg.end(), [](char c) {
        return std::isdigit(static_cast<unsigned char>(c));
    });
    if (!counted && scenes.size() != 1)
        throw InputError("--views " + viewsArg + ": a views file fits one scene; give a count for several");
    view::ViewSampling sampling;
    sampling.count = counted ? args.integer("--views", 0, 1, 100000) : 0;
    sampling.seed = std::uint64_t(args.integer("--view-seed", 1, 0, 1 << 30));
    std::vector<std::vector<Camera>> views;
    for (const Scene& scene : scenes) views.push_back(counted ? view::sampleViews(scene, sampling) : view::readViews(viewsArg, scene));
    return views;
}

int runViewsEvaluation(const Args& args, const std::string& dir, const std::vector<Scene>& scenes,
                       const std::vector<RenderSettings>& settings, const std::vector<std::vector<Camera>>& views, const std::vector<std::string>& methodNames,
                       const std::vector<std::string>& presetNames, int spp, const std::string& cacheDir,
                       const ReportInfo& info) {
    std::vector<ViewsEval> results;
    for (std::size_t si = 0; si < scenes.size(); ++si) {
        const std::string name = sceneName(args.positional()[si]);
        ViewsJob job;
        for (const std::string& method : methodNames)
            for (const Preset& preset : presetsFor(findMethod(method), presetNames)) job.runs.push_back({method, preset});
        job.settings = settings[si];
        job.spp = spp;
        job.caustics = !args.flag("--no-caustics");
        job.cacheDir = cacheDir;
        std::filesystem::create_directories(dir + "/" + name);
        ViewsEval e = evaluateViews(scenes[si], name, views[si], job, dir);
        e.source = args.positional()[si];
        e.viewsFile = name + "/views.json";
        view::writeViews(dir + "/" + e.viewsFile, views[si]);
        results.push_back(std::move(e));
    }
    const std::vector<std::string> plots = writeViewsReport(dir, results, info);
    std::printf("wrote %s/views.md, views.json, views.csv%s\n", dir.c_str(),
                info.gnuplot ? (" and " + std::to_string(plots.size()) + " plots").c_str() : " (gnuplot not found: no plots)");
    return kOk;
}

int runEvaluation(const Args& args, const std::string& dir, const std::vector<std::string>& argv) {
    if (args.positional().empty()) throw InputError("give at least one SCENE; usage: " + usageLine(kUsage));
    std::string allBuilt;
    for (const std::string& m : builtMethods()) allBuilt += (allBuilt.empty() ? "" : ",") + m;
    const std::vector<std::string> methodNames = splitList(args.value("--methods", allBuilt));
    const std::vector<std::string> presetNames = splitList(args.value("--presets", "low,medium,high"));
    if (methodNames.empty()) throw InputError("--methods: empty list");
    for (const std::string& m : methodNames) {
        try {
            findMethod(m);
        } catch (const InputError& e) {
            throw InputError(std::string("--methods ") + e.what());
        }
    }
    requireKnownPresets(presetNames);
    const std::string refArg = args.value("--reference", "auto");
    if (refArg != "auto" && args.positional().size() != 1)
        throw InputError("--reference " + refArg + ": a reference file fits one scene; use auto for several");
    const int spp = args.integer("--spp", 256, 1, 1 << 20);
    const std::string cacheDir = args.value("--cache", dir + "/cache");
    const bool views = args.has("--views");
    if (refArg != "auto" && args.flag("--no-caustics"))
        throw InputError("--no-caustics: applies to the references eval path traces; a given --reference is used as it is");
    if (views && refArg != "auto") throw InputError("--reference: each of --views has its own reference; leave it auto");
    if (!views && args.has("--view-seed")) throw InputError("--view-seed: only with --views");

    std::vector<Scene> scenes;
    std::vector<RenderSettings> sceneSettings;
    for (const std::string& s : args.positional()) {
        scenes.push_back(loadSceneArgument(s));
        applySceneOverrides(args, scenes.back());
        for (const std::string& m : methodNames) validateMethod(m, scenes.back());
        sceneSettings.push_back(renderSettingsFor(args, scenes.back()));
    }
    const std::vector<std::vector<Camera>> sceneViews = views ? viewsFor(args, scenes) : std::vector<std::vector<Camera>>{};
    // Only once every input has been read, so bad input leaves no folder behind.
    makeOutputFolder(dir);
    auto context = gl::Context::createHeadless();
    ReportInfo info;
    info.device = context->description();
    info.gnuplot = gnuplotAvailable();
    info.command = "voxgi eval";
    for (const std::string& a : argv) info.command += " " + a;

    if (views) return runViewsEvaluation(args, dir, scenes, sceneSettings, sceneViews, methodNames, presetNames, spp, cacheDir, info);

    std::vector<SceneEval> results;
    for (std::size_t si = 0; si < scenes.size(); ++si) {
        const Scene& scene = scenes[si];
        SceneEval se;
        se.name = sceneName(args.positional()[si]);
        se.source = args.positional()[si];
        se.width = scene.camera.width;
        se.height = scene.camera.height;
        std::filesystem::create_directories(dir + "/" + se.name);
        std::printf("%s: reference...\n", se.name.c_str());
        std::fflush(stdout);
        Reference ref = refArg == "auto" ? loadOrRenderReference(scene, se.name, spp, cacheDir, !args.flag("--no-caustics"))
                                         : readReference(refArg, scene);
        se.referenceSpp = ref.spp;
        se.referenceSeconds = ref.seconds;
        se.referenceCached = ref.fromCache;
        se.referenceCaustics = refArg != "auto" || !args.flag("--no-caustics");
        se.referencePath = ref.path;
        se.referenceMeanIndirect = layerMean(ref.image, "indirect");
        se.selfFull = computeMetrics(ref.image, ref.image, "beauty");
        se.selfIndirect = computeMetrics(ref.image, ref.image, "indirect");
        se.referencePng = se.name + "/reference.png";
        writePng(dir + "/" + se.referencePng, ref.image, "beauty", 0.0f);

        const RenderSettings& rs = sceneSettings[si];
        std::vector<Image> images;
        for (const std::string& method : methodNames)
            for (const Preset& preset : presetsFor(findMethod(method), presetNames)) {
                std::printf("%s: %s %s...\n", se.name.c_str(), method.c_str(), preset.name.c_str());
                std::fflush(stdout);
                const MethodInfo& info = findMethod(method);
                SettingList fitted;
                if (info.oracle()) {
                    RenderWith render = [&](const SettingList& extra) {
                        return renderMethod(scene, method, preset, rs, extra).image;
                    };
                    fitted = info.fitToReference(render, ref.image);
                }
                MethodRun run = renderMethod(scene, method, preset, rs, fitted);
                EvalRow row = measure(method, preset, run, ref, dir, se.name);
                row.oracle = info.oracle();
                row.fitted = settingsText(fitted);
                std::printf("  %.2f ms/frame, RMSE %.4g FLIP %.4g (full), RMSE %.4g FLIP %.4g (indirect)\n",
                            row.frameMs, row.full.rmse, row.full.flip, row.indirect.rmse, row.indirect.flip);
                se.rows.push_back(row);
                images.push_back(std::move(run.image));
            }
        std::vector<const Image*> crops{&ref.image};
        for (const Image& im : images) crops.push_back(&im);
        se.cropsPng = se.name + "/crops.png";
        writeCrops(dir + "/" + se.cropsPng, crops);
        results.push_back(std::move(se));
    }
    std::vector<std::string> plots = writeEvalReport(dir, results, info);
    std::printf("wrote %s/report.md, report.json, results.csv%s\n", dir.c_str(),
                info.gnuplot ? (" and " + std::to_string(plots.size()) + " plots").c_str()
                             : " (gnuplot not found: no plots)");
    return kOk;
}

int runEval(const std::vector<std::string>& argv) {
    Args args(argv,
              {"-o", "--methods", "--presets", "--reference", "--spp", "--cache", "--frames", "--warmup", "--converge",
               "--max-warmup", "--width", "--height", "--set", "--cases", "--views", "--view-seed"},
              {"--stability", "--no-caustics"}, {"--set"});
    auto out = args.value("-o");
    if (!out) throw InputError("-o DIR is required; usage: " + usageLine(kUsage));
    if (args.flag("--stability")) {
        makeOutputFolder(*out);
        if (!args.positional().empty()) throw InputError("--stability takes no SCENE (its scenes are built in)");
        auto cases = args.value("--cases");
        return runStabilitySuite(*out, cases ? splitList(*cases) : std::vector<std::string>{}) ? kOk : kFailure;
    }
    if (args.has("--cases")) throw InputError("--cases: only with --stability");
    return runEvaluation(args, *out, argv);
}

}  // namespace

VOXGI_REGISTER_COMMAND("eval", kUsage, runEval);

}  // namespace voxgi::cli
