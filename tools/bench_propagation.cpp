// voxgi bench propagation: the CPU LPV propagator (gi/lpv/propagation.h) against this machine's
// memory bandwidth. One cascade fitted to the scene's bounds at each resolution, its static
// blockers from the voxelized scene, light in every cell (so every brick runs every step), and
// the cell-steps per second set beside the limit the STREAM triad puts on them.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include "gi/lpv/propagation.h"
#include "gi/lpv/static_blockers.h"
#include "scenes/errors.h"
#include "scenes/scene_loader.h"
#include "tools/args.h"
#include "tools/bench_registry.h"
#include "tools/memory_bandwidth.h"
#include "tools/scene_arg.h"
#include "volumes/geometry_volume.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi bench propagation [SCENE] [--resolutions 32,64,128] [--steps 16] [--threads 1,0] [--repeats 3]\n"
    "       [--open] [--pairs auto|never|always]\n"
    "  CPU LPV propagation of one cascade over SCENE's bounds (default cornell-box) with its static\n"
    "  blockers and light in every cell: million cell-steps per second and the share of the limit\n"
    "  that the STREAM triad (measured in the same run, same threads) puts on them at the 192 bytes\n"
    "  a cell-step must move (12 floats read, 12 written, 12 accumulated). --threads: a list (0: all);\n"
    "  each timing is the best of N runs. --open: no blockers (the light's own traffic alone);\n"
    "  --pairs: two steps per pass through memory (CpuPropagator::setStepPairs; auto: from\n"
    "  the resolution)";

// Bytes one cell-step must move at the least: the source cell's 12 coefficients read (its
// neighbours' come from cache), the output's 12 written and the running sum's 12 read and written.
constexpr double kBytesPerCellStep = 4.0 * (12 + 12 + 2 * 12);

struct Cascade {
    LightVolume light;
    BlockerVolume blockers;
};

Cascade fitCascade(const Scene& scene, int resolution) {
    const Bounds bounds = scene.bounds();
    const glm::vec3 extent = bounds.extent();
    // One cell of margin around the scene, as the whole scene must fit inside the cascade.
    const float cell = std::max(extent.x, std::max(extent.y, extent.z)) / float(resolution - 2);
    VoxelizeSettings settings;
    settings.voxelSize = cell;
    settings.maxVoxels = std::uint64_t(1) << 32;
    const SparseGeometryVolume voxels = voxelizeScene(scene, settings);
    Cascade c;
    CascadeGrid grid;
    grid.resolution = resolution;
    grid.cellSize = cell;
    grid.origin = glm::ivec3(glm::floor(bounds.min / cell)) - 1;
    c.blockers.reset(grid);
    staticBlockers(voxels, 0, c.blockers);
    c.light.reset(grid);
    // Light everywhere, with a direction, so that no brick is ever skipped.
    for (std::vector<glm::vec4>* colour : {&c.light.r, &c.light.g, &c.light.b})
        std::fill(colour->begin(), colour->end(), glm::vec4(1.0f, 0.1f, 0.2f, 0.3f));
    return c;
}

int benchPropagation(const std::vector<std::string>& argv) {
    Args args(argv, {"--resolutions", "--steps", "--threads", "--repeats", "--pairs"}, {"--open"});
    const std::string sceneName = args.positional().empty() ? "cornell-box" : args.positional()[0];
    const std::vector<int> resolutions = args.integers("--resolutions", "32,64,128", 8, 512);
    const std::vector<int> threads = args.integers("--threads", "1,0", 0, 1024);
    const int steps = args.integer("--steps", 16, 1, 100000);
    const int repeats = args.integer("--repeats", 3, 1, 100);
    const Scene scene = loadSceneArgument(sceneName);
    PropagationOptions options;
    options.occlusion = !args.flag("--open");
    const std::string pairsName = args.value("--pairs", "auto");
    if (pairsName != "auto" && pairsName != "never" && pairsName != "always")
        throw InputError("--pairs: expected auto, never or always, got '" + pairsName + "'");
    const auto pairs = pairsName == "never"    ? CpuPropagator::StepPairs::Never
                       : pairsName == "always" ? CpuPropagator::StepPairs::Always
                                               : CpuPropagator::StepPairs::Auto;

    std::printf("%s: %zu triangles%s; %d steps, best of %d; %.0f bytes per cell-step\n", sceneName.c_str(),
                scene.triangleCount(), options.occlusion ? "" : " (not blocking: --open)", steps, repeats,
                kBytesPerCellStep);
    std::printf("%5s %7s | %7s %7s | %9s %9s %8s %9s | %7s %9s %7s\n", "res", "threads", "occl %", "bounce %",
                "steps ms", "op ms", "Mcell/s", "GB/s", "triad", "limit M/s", "share");
    for (int t : threads) {
        const int count = t > 0 ? t : tbb::info::default_concurrency();
        const double triad = streamTriadGBs(count);
        const double limit = triad * 1e9 / kBytesPerCellStep;
        tbb::task_arena arena(count);
        for (int res : resolutions) {
            const Cascade cascade = fitCascade(scene, res);
            CpuPropagator propagator;
            propagator.setStepPairs(pairs);
            LightVolume accumulated;
            double best = 1e30, operatorMs = 0.0;
            int stepsRun = 0;
            PropagationStats built;
            arena.execute([&] {
                // The first call builds the operator; the timed ones keep it, as a static scene does.
                propagator.propagate(cascade.light, cascade.blockers, steps, options, accumulated, false);
                built = propagator.stats();
                operatorMs = built.operatorMs;
                for (int r = 0; r < repeats; ++r) {
                    propagator.propagate(cascade.light, cascade.blockers, steps, options, accumulated, false);
                    best = std::min(best, propagator.stats().stepsMs);
                    stepsRun = propagator.stats().stepsRun;
                }
            });
            const double cellSteps = double(res) * res * res * stepsRun;
            const double rate = cellSteps / (best * 1e-3);
            const double runs = double(std::max<std::size_t>(built.runs, 1));
            std::printf("%5d %7d | %7.1f %8.1f | %9.2f %9.2f %8.1f %9.2f | %7.2f %9.1f %6.0f %%\n", res, count,
                        100.0 * double(built.occludedRuns) / runs, 100.0 * double(built.bounceRuns) / runs, best,
                        operatorMs, rate * 1e-6, rate * kBytesPerCellStep * 1e-9, triad, limit * 1e-6,
                        100.0 * rate / limit);
            std::fflush(stdout);
        }
    }
    std::printf("occl %%, bounce %%: runs of 8 cells with an occluded side, next to a reflecting blocker;\n"
                "steps ms: the propagation alone (best run; operator kept); op ms: building the operator once;\n"
                "triad: STREAM triad GB/s on the same threads; limit: triad / bytes per cell-step; share: Mcell/s / limit\n");
    return kOk;
}

}  // namespace

VOXGI_REGISTER_BENCHMARK("propagation", kUsage, benchPropagation);

}  // namespace voxgi::cli
