// voxgi bench lpv: per-stage LPV/CLPV timings (RSM, injection, blockers, propagation, apply)
// for the built-in Cornell box and, when ../shared/scenes is present, Sibenik and Sponza, at
// two resolutions and with both back ends; plus sparse against dense CPU propagation.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "render/frame/frame_renderer.h"
#include "render/frame/techniques.h"
#include "gl/context.h"
#include "scenes/errors.h"
#include "scenes/image.h"
#include "scenes/scene_loader.h"
#include "tools/bench_registry.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi bench lpv [--scenes cornell-box,sibenik,sponza] [--sizes 512,1024] [--backends cpu,gl] [--frames N]\n"
    "                [--steps S] [--cascades C] [-o results.csv]";

std::vector<std::string> split(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

struct Row {
    std::string scene, backend, mode;
    int size;
    std::map<std::string, double> stageMs;
};

// A stage's cost: the larger of its GPU and CPU medians. A GPU stage's CPU time is only its
// submission on a real GPU, but llvmpipe runs compute dispatches on the calling thread and its
// timer queries read 0 for them (propagation, the blocker merges), so there the CPU time is it.
double median(const gl::StageTimers& t, const std::string& stage) {
    auto it = t.samples().find(stage);
    if (it == t.samples().end()) return 0.0;
    return std::max(gl::summarize(it->second.gpuMs).median, gl::summarize(it->second.cpuMs).median);
}

int runBenchLpv(const std::vector<std::string>& argv) {
    Args args(argv, {"--scenes", "--sizes", "--backends", "--frames", "--steps", "--cascades", "-o"}, {});
    auto scenes = split(args.value("--scenes", "cornell-box,sibenik,sponza"));
    auto sizes = split(args.value("--sizes", "512,1024"));
    auto backends = split(args.value("--backends", "cpu,gl"));
    const int frames = args.integer("--frames", 5, 1, 1000);
    const int steps = args.integer("--steps", 16, 0, 100000);
    const int cascades = args.integer("--cascades", 3, 1, 6);
    if (auto o = args.value("-o")) requireWritable(*o, "-o");
    auto context = gl::Context::createHeadless();
    std::printf("device: %s\n", context->description().c_str());
    const std::vector<std::string> stages = {"lpv.rsm", "lpv.gbuffer_readback", "lpv.inject", "lpv.blockers",
                                             "lpv.propagate", "lpv.propagate_operator", "lpv.propagate_steps", "lpv.upload",
                                             "lpv.apply"};
    std::vector<Row> rows;
    for (const std::string& name : scenes) {
        Scene scene;
        try {
            scene = loadSceneArgument(name);
        } catch (const InputError& e) {
            std::printf("%s: skipped (%s)\n", name.c_str(), e.what());
            continue;
        }
        for (const std::string& size : sizes)
            for (const std::string& backend : backends)
                for (const std::string mode : {"sparse", "dense"}) {
                    if (backend == "gl" && mode == "dense") continue;  // the GL path is always dense
                    Scene s = scene;
                    s.camera.width = s.camera.height = std::stoi(size);
                    s.gi.set("lpv.backend", backend);
                    s.gi.set("lpv.steps", std::to_string(steps));
                    s.gi.set("lpv.cascades", std::to_string(cascades));
                    s.gi.set("lpv.sparse", mode == "sparse" ? "true" : "false");
                    s.gi.set("lpv.reuse", "false");
                    FrameRenderer r(s, FrameOptions{}, createTechnique("clpv", s));
                    r.renderFrame();  // warm-up: shader compilation, first uploads
                    FrameRenderer timed(s, FrameOptions{}, createTechnique("clpv", s));
                    for (int f = 0; f < frames; ++f) timed.renderFrame();
                    Row row{name, backend, backend == "gl" ? "dense" : mode, s.camera.width, {}};
                    for (const auto& st : stages) row.stageMs[st] = median(timed.timers(), st);
                    rows.push_back(row);
                    std::printf("%-12s %4dx%-4d %-3s %-6s", name.c_str(), row.size, row.size, backend.c_str(),
                                row.mode.c_str());
                    for (const auto& st : stages) std::printf(" %s %.2f", st.substr(4).c_str(), row.stageMs[st]);
                    std::printf("  (ms, median of %d frames)\n", frames);
                }
    }
    if (auto o = args.value("-o")) {
        std::string tmp = temporaryPathFor(*o);
        {
            std::ofstream out(tmp);
            out << "scene,size,backend,mode,cascades,steps";
            for (const auto& st : stages) out << "," << st << "_ms";
            out << "\n";
            for (const Row& row : rows) {
                out << row.scene << "," << row.size << "," << row.backend << "," << row.mode << "," << cascades << ","
                    << steps;
                for (const auto& st : stages) out << "," << row.stageMs.at(st);
                out << "\n";
            }
        }
        renameInto(tmp, *o);
        std::printf("wrote %s\n", o->c_str());
    }
    return kOk;
}

}  // namespace

VOXGI_REGISTER_BENCHMARK("lpv", kUsage, runBenchLpv);

}  // namespace voxgi::cli
