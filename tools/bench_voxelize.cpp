// voxgi bench voxelize: the full geometry grid set (occupancy, albedo, normal, blocker) against
// OpenVDB's meshToVolume (unsigned distance, half width 1) on the same mesh and voxel size.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "scenes/scene_loader.h"
#include "tools/args.h"
#include "tools/bench_registry.h"
#include "tools/scene_arg.h"
#include "volumes/geometry_volume.h"
#include "volumes/openvdb_reference.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi bench voxelize [SCENE] [--resolutions 128,256,512] [--repeats N]\n"
    "  SCENE defaults to ../shared/scenes/crytek-sponza/sponza.obj; resolutions are voxels across\n"
    "  the longest side; each timing is the best of N runs (default 3)";

// $VOXGI_SCENES, else the shared scene folder beside the source tree.
std::string defaultScene() {
    std::filesystem::path dir;
    if (const char* env = std::getenv("VOXGI_SCENES")) dir = env;
    else dir = std::filesystem::path(builtinScenePath("cornell-box")).parent_path().parent_path().parent_path() / "shared" / "scenes";
    return (dir / "crytek-sponza" / "sponza.obj").string();
}

double mib(std::uint64_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

int benchVoxelize(const std::vector<std::string>& argv) {
    Args args(argv, {"--resolutions", "--repeats"}, {});
    std::string scenePath = args.positional().empty() ? defaultScene() : args.positional()[0];
    std::vector<int> resolutions = args.integers("--resolutions", "128,256,512", 1, 8192);
    int repeats = args.integer("--repeats", 3, 1, 100);

    auto loadStart = std::chrono::steady_clock::now();
    Scene scene = loadSceneArgument(scenePath);
    double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count();
    Bounds bounds = scene.bounds();
    glm::vec3 ext = bounds.extent();
    float longest = std::max(ext.x, std::max(ext.y, ext.z));
    std::printf("scene %s: %zu triangles, longest side %g, loaded in %.2f s\n", scenePath.c_str(),
                scene.triangleCount(), double(longest), loadSeconds);
    std::printf("%5s %8s | %7s %7s %7s %9s %6s %7s %8s | %7s %7s %9s %6s %7s %8s | %5s %5s %5s %5s\n", "res",
                "voxel", "voxgi s", "cpu s", "Mtri/s", "active", "leaves", "MiB", "peak MiB", "m2v s", "cpu s", "active",
                "leaves", "MiB", "peak MiB", "time", "cpu", "mem", "peak");
    for (int res : resolutions) {
        VoxelizeSettings settings;
        settings.voxelSize = longest / float(res);
        settings.maxVoxels = std::uint64_t(1) << 34;
        double best = 1e30, bestCpu = 1e30, peak = 0.0;
        std::uint64_t active = 0, bytes = 0, leaves = 0;
        for (int r = 0; r < repeats; ++r) {
            const PeakResidentMemory memory;
            double cpuStart = processCpuSeconds();
            SparseGeometryVolume v = voxelizeScene(scene, settings);
            bestCpu = std::min(bestCpu, processCpuSeconds() - cpuStart);
            peak = memory.peakBytes();
            best = std::min(best, v.stats().seconds);
            active = v.activeVoxelCount();
            bytes = v.memoryBytes();
            leaves = v.activeBricks(0).size();
        }
        MeshToVolumeRun baseline;
        baseline.seconds = baseline.cpuSeconds = 1e30;
        double baselinePeak = 0.0;
        for (int r = 0; r < repeats; ++r) {
            MeshToVolumeRun run = runMeshToUnsignedDistance(scene, settings.voxelSize, 1.0f);
            baselinePeak = run.peakBytes;
            baseline.cpuSeconds = std::min(baseline.cpuSeconds, run.cpuSeconds);
            if (run.seconds < baseline.seconds) {
                double cpu = baseline.cpuSeconds;
                baseline = run;
                baseline.cpuSeconds = cpu;
            }
        }
        using ull = unsigned long long;
        std::printf("%5d %8.4g | %7.3f %7.3f %7.2f %9llu %6llu %7.1f %8.1f | %7.3f %7.3f %9llu %6llu %7.1f %8.1f | %5.2f "
                    "%5.2f %5.2f %5.2f\n",
                    res, double(settings.voxelSize), best, bestCpu, double(scene.triangleCount()) / best / 1e6,
                    ull(active), ull(leaves), mib(bytes), peak / 1048576.0, baseline.seconds, baseline.cpuSeconds,
                    ull(baseline.activeVoxels), ull(baseline.leafCount), mib(baseline.memoryBytes),
                    baselinePeak / 1048576.0, best / baseline.seconds, bestCpu / baseline.cpuSeconds,
                    double(bytes) / double(baseline.memoryBytes), peak / baselinePeak);
        std::fflush(stdout);
    }
    std::printf("time, cpu, mem, peak: voxgi / meshToVolume, best of %d (goal: time <= 0.5, peak <= 1.2); voxgi MiB =\n"
                "occupancy tree + compact attribute arrays, m2v MiB = its FloatGrid's memUsage; peak MiB = the most\n"
                "resident memory of the last run above the process's before it (NaN: /proc does not say)\n", repeats);
    return kOk;
}

}  // namespace

VOXGI_REGISTER_BENCHMARK("voxelize", kUsage, benchVoxelize);

}  // namespace voxgi::cli
