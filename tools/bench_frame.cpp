// voxgi bench METHOD / voxgi bench frame --method METHOD: a method's whole frame on scenes, sizes
// and its benchmark variants side by side (gi/method.h benchVariants: the LPV's back ends, say),
// with the median of every stage timer and of every technique stat over the timed frames. A
// method with a benchmark of its own (ddgi) runs that one for `voxgi bench METHOD`.
#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>

#include <tbb/global_control.h>

#include "gi/methods.h"
#include "gl/context.h"
#include "scenes/atomic_file.h"
#include "scenes/errors.h"
#include "tools/bench_registry.h"
#include "tools/eval_run.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi bench frame --method NAME [SCENE...] [--sizes 512,1024] [--variants A,B] [--frames N] [--warmup N]\n"
    "                  [--threads N] [--set k=v]... [-o results.csv]\n"
    "  also `voxgi bench NAME` for a method without a benchmark of its own; SCENE: default cornell-box and,\n"
    "  when ../shared/scenes is there, sibenik and sponza; variants: the method's (voxgi methods NAME);\n"
    "  a size is N (square) or WxH (1920x1080). A stage prints the larger of its GPU and CPU medians as\n"
    "  STAGE_ms and, where the GPU timed it, its GPU median alone as STAGE_gpu_ms";

// Scenes named on the command line, else the defaults that load (a missing mesh is skipped).
std::vector<std::pair<std::string, Scene>> benchScenes(const Args& args) {
    const bool given = !args.positional().empty();
    const std::vector<std::string> names = given ? args.positional() : std::vector<std::string>{"cornell-box", "sibenik", "sponza"};
    std::vector<std::pair<std::string, Scene>> scenes;
    for (const std::string& name : names) {
        try {
            Scene s = loadSceneArgument(name);
            applySceneOverrides(args, s);
            scenes.emplace_back(name, std::move(s));
        } catch (const InputError& e) {
            if (given) throw;
            std::printf("%s: skipped (%s)\n", name.c_str(), e.what());
        }
    }
    return scenes;
}

struct ImageSize {
    int width = 0, height = 0;
};

struct Row {
    std::string scene, variant;
    ImageSize size;
    std::map<std::string, double> values;  // "<stage>_ms" and technique stats
};

// One scene, size and variant: warm-up frames, then the medians of the timed ones (eval's
// renderMethod), the user's --set over the variant's settings.
Row benchOne(const std::string& name, const Scene& scene, ImageSize size, const MethodInfo& method, const Preset& variant,
             const Args& args, int warmup, int frames) {
    GiSettings user;
    for (const std::string& s : args.values("--set")) user.applyOverride(s);
    const SettingList extra(user.values().begin(), user.values().end());
    RenderSettings settings;
    settings.width = size.width;
    settings.height = size.height;
    settings.warmup = warmup;
    settings.frames = warmup + frames;
    const MethodRun run = renderMethod(scene, method.name, variant, settings, extra);
    Row row{name, variant.name, size, {}};
    // llvmpipe runs compute on the calling thread and its timer queries read 0 for it: a stage
    // costs the larger of its GPU and CPU medians.
    // On a real GPU the CPU time of a stage is often only its submission: the GPU time alone is
    // what a GPU goal is judged by.
    for (const auto& [stage, t] : run.stages) {
        if (t.samples == 0) continue;
        row.values[stage + "_ms"] = std::fmax(t.gpuMs, t.cpuMs);  // fmax skips a NaN GPU time
        if (t.gpuMs > 0) row.values[stage + "_gpu_ms"] = t.gpuMs;
    }
    for (const auto& [stat, value] : run.stats) row.values[stat] = value;
    // The whole frame, wall clock (stages that overlap, such as hybrid.overlap's tracing, count once).
    row.values["frame_ms"] = run.frameMs;
    return row;
}

int runFrameBench(const MethodInfo& method, const Args& args) {
    const std::vector<std::string> sizes = splitList(args.value("--sizes", "512,1024"));
    const int frames = args.integer("--frames", 5, 1, 1000);
    const int warmup = args.integer("--warmup", 1, 0, 1000);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              std::size_t(args.integer("--threads", 2, 1, 1024)));
    std::vector<Preset> variants = method.benchVariants.empty() ? std::vector<Preset>{{"default", {}}} : method.benchVariants;
    if (auto wanted = args.value("--variants")) {
        std::vector<Preset> chosen;
        for (const std::string& w : splitList(*wanted)) {
            auto it = std::find_if(variants.begin(), variants.end(), [&](const Preset& p) { return p.name == w; });
            if (it == variants.end()) throw InputError("--variants " + w + ": not a variant of " + method.name);
            chosen.push_back(*it);
        }
        variants = chosen;
    }
    std::vector<ImageSize> pixels;
    for (const std::string& s : sizes) {
        auto side = [&](const char* from, char** end) {
            const long v = std::strtol(from, end, 10);
            if (*end == from || v < 8 || v > 16384)
                throw InputError("--sizes " + s + ": expected N or WxH, sides in [8, 16384]");
            return int(v);
        };
        char* end = nullptr;
        ImageSize size;
        size.width = size.height = side(s.c_str(), &end);
        if (*end == 'x') size.height = side(end + 1, &end);
        if (*end != '\0') throw InputError("--sizes " + s + ": expected N or WxH, sides in [8, 16384]");
        pixels.push_back(size);
    }
    if (auto o = args.value("-o")) requireWritable(*o, "-o");
    const auto scenes = benchScenes(args);
    auto context = gl::Context::createHeadless();
    std::printf("voxgi bench %s: %s, medians of %d frames after %d warm-up (ms, or the stat's unit)\n",
                method.name.c_str(), context->description().c_str(), frames, warmup);
    std::vector<Row> rows;
    for (const auto& [name, scene] : scenes)
        for (ImageSize size : pixels)
            for (const Preset& variant : variants) {
                rows.push_back(benchOne(name, scene, size, method, variant, args, warmup, frames));
                std::printf("%-12s %4dx%-4d %-10s", name.c_str(), size.width, size.height, variant.name.c_str());
                for (const auto& [key, value] : rows.back().values) std::printf(" %s %.4g", key.c_str(), value);
                std::printf("\n");
                std::fflush(stdout);
            }
    if (auto o = args.value("-o")) {
        std::vector<std::string> columns;
        for (const Row& r : rows)
            for (const auto& [key, value] : r.values)
                if (std::find(columns.begin(), columns.end(), key) == columns.end()) columns.push_back(key);
        std::ostringstream csv;
        csv << "method,scene,size,variant";
        for (const std::string& c : columns) csv << "," << c;
        csv << "\n";
        for (const Row& r : rows) {
            csv << method.name << "," << r.scene << "," << r.size.width << "x" << r.size.height << "," << r.variant;
            for (const std::string& c : columns) csv << "," << (r.values.count(c) ? r.values.at(c) : 0.0);
            csv << "\n";
        }
        writeTextAtomically(*o, csv.str());
        std::printf("wrote %s\n", o->c_str());
    }
    return kOk;
}

const std::set<std::string> kValued = {"--method", "--sizes", "--variants", "--frames", "--warmup", "--threads",
                                       "--set", "-o"};

int runBenchFrame(const std::vector<std::string>& argv) {
    Args args(argv, kValued, {}, {"--set"});
    auto method = args.value("--method");
    if (!method) throw InputError("--method NAME is required; usage: " + usageLine(kUsage));
    try {
        findMethod(*method);
    } catch (const InputError& e) {
        throw InputError(std::string("--method ") + e.what());
    }
    return runFrameBench(findMethod(*method), args);
}

// A method's own benchmark with the scenes and counts of the command line.
int runMethodBench(const MethodInfo& method, const std::vector<std::string>& argv) {
    Args args(argv, {"--frames", "--warmup", "--threads", "--set", "--width", "--height", "--backend"}, {"--no-gl"},
              {"--set"});
    BenchRequest request;
    request.frames = args.has("--frames") ? args.integer("--frames", 5, 1, 1000) : 0;
    request.warmup = args.has("--warmup") ? args.integer("--warmup", 1, 0, 1000) : 0;
    request.threads = args.integer("--threads", 2, 1, 1024);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(request.threads));
    request.scenes = benchScenes(args);
    std::unique_ptr<gl::Context> context;
    if (!args.flag("--no-gl")) {
        try {
            context = gl::Context::createHeadless();
            request.gl = true;
            request.device = context->description();
        } catch (const gl::GlError& e) {
            std::printf("(no GL context: %s)\n", e.what());
        }
    }
    method.bench(request);
    return kOk;
}

}  // namespace

int runBenchForMethod(const std::string& name, const std::vector<std::string>& argv) {
    const MethodInfo& method = findMethod(name);
    if (method.bench) return runMethodBench(method, argv);
    Args args(argv, kValued, {}, {"--set"});
    return runFrameBench(method, args);
}

VOXGI_REGISTER_BENCHMARK("frame", kUsage, runBenchFrame);

}  // namespace voxgi::cli
