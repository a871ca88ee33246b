// voxgi bench limits: the bounds this machine puts on the CPU back end, so that every throughput
// ratio in the docs has its denominator beside it: memory bandwidth (STREAM triad) for the
// streaming kernels (LPV propagation, `voxgi bench propagation`) and Embree's own ray throughput
// for the path tracer (`voxgi bench pathtrace`).
#include <algorithm>
#include <cstdio>
#include <optional>
#include <utility>

#include <tbb/info.h>

#include "gi/pathtrace/path_tracer.h"
#include "tools/args.h"
#include "tools/bench_registry.h"
#include "tools/embree_share.h"
#include "tools/memory_bandwidth.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi bench limits [--scenes cornell-box,sibenik,sponza] [--size 128] [--spp 4] [--threads 1,0]\n"
    "  STREAM triad GB/s on each thread count of --threads (0: all), and per scene Embree's own\n"
    "  rays per CPU second (rtcIntersect1 / rtcOccluded1) on the rays the path tracer casts for\n"
    "  --spp samples at --size^2, beside the path tracer's on the same rays. Scenes whose meshes are\n"
    "  absent are skipped.";

int benchLimits(const std::vector<std::string>& argv) {
    Args args(argv, {"--scenes", "--size", "--spp", "--threads"}, {});
    const std::vector<std::string> scenes = splitList(args.value("--scenes", "cornell-box,sibenik,sponza"));
    const int size = args.integer("--size", 128, 8, 4096);
    const int spp = args.integer("--spp", 4, 1, 1 << 16);
    const std::vector<int> threads = args.integers("--threads", "1,0", 0, 1024);
    // Every scene is read before anything is measured, so a bad one stops the run at once.
    std::vector<std::pair<std::string, Scene>> loaded;
    for (const std::string& name : scenes)
        if (std::optional<Scene> scene = loadBenchScene(name)) loaded.emplace_back(name, std::move(*scene));

    std::printf("memory bandwidth (STREAM triad, 3 x 128 MB of doubles, best of 5):\n");
    for (int t : threads) {
        const int count = t > 0 ? t : tbb::info::default_concurrency();
        std::printf("  %2d thread%s: %6.2f GB/s\n", count, count == 1 ? " " : "s", streamTriadGBs(count));
        std::fflush(stdout);
    }
    std::printf("Embree alone on the path tracer's rays (%dx%d, %d spp, %d threads; M rays per CPU s):\n", size,
                size, spp, tbb::info::default_concurrency());
    for (auto& [name, scene] : loaded) {
        scene.camera.width = scene.camera.height = size;
        PathTracer tracer(scene, PathTracerOptions{});
        tracer.render(1);  // warm caches and page in the scene
        const EmbreeShare share = measureEmbreeShare(tracer, spp);
        std::printf("  %-12s %8.3g rays: Embree %6.2f, path tracer %6.2f (%.0f %%)\n", name.c_str(), share.rays,
                    share.barePerCpuS * 1e-6, share.pathPerCpuS * 1e-6, 100.0 * share.pathPerCpuS / share.barePerCpuS);
        std::fflush(stdout);
    }
    return kOk;
}

}  // namespace

VOXGI_REGISTER_BENCHMARK("limits", kUsage, benchLimits);

}  // namespace voxgi::cli
