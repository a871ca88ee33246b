// voxgi voxelize: a scene or mesh -> sparse geometry volumes (.vdb), one grid set per level.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>

#include <unistd.h>

#include "scenes/errors.h"
#include "tools/commands.h"
#include "tools/scene_arg.h"
#include "volumes/geometry_volume.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi voxelize SCENE_OR_MESH --voxel-size S -o OUT.vdb [--levels N] [--max-voxels M] [--sdf]\n"
    "       [--blocker-fit plane-exact|projection]\n"
    "  --levels: cascade levels, voxel size doubling per level (default 1)\n"
    "  --max-voxels: refuse when the estimated voxel count is larger (default 67108864)\n"
    "  --sdf: add a narrow-band signed distance grid 'sdf' (watertight meshes)";

// A text bar on stderr, only on a terminal and only once a run has taken a moment.
class ProgressBar {
public:
    ProgressBar() : start_(std::chrono::steady_clock::now()), enabled_(isatty(2)) {}
    void update(float fraction) {
        if (!enabled_) return;
        int percent = int(fraction * 100.0f);
        std::lock_guard<std::mutex> lock(mutex_);
        if (percent <= shown_) return;
        if (std::chrono::steady_clock::now() - start_ < std::chrono::milliseconds(500)) return;
        shown_ = percent;
        int filled = percent * 40 / 100;
        std::fprintf(stderr, "\rvoxelizing [%.*s%*s] %3d%%", filled, "########################################",
                     40 - filled, "", percent);
        std::fflush(stderr);
        drawn_ = true;
    }
    ~ProgressBar() {
        if (drawn_) std::fprintf(stderr, "\n");
    }

private:
    std::chrono::steady_clock::time_point start_;
    bool enabled_;
    bool drawn_ = false;
    int shown_ = -1;
    std::mutex mutex_;
};

int runVoxelize(const std::vector<std::string>& argv) {
    Args args(argv, {"--voxel-size", "-o", "--levels", "--max-voxels", "--blocker-fit"}, {"--sdf"});
    args.requirePositional(1, kUsage);
    if (!args.has("--voxel-size")) throw InputError("--voxel-size S is required; usage: " + usageLine(kUsage));
    auto out = args.value("-o");
    if (!out) throw InputError("-o OUT.vdb is required; usage: " + usageLine(kUsage));
    requireOutputs(args, {"-o"});

    VoxelizeSettings settings;
    settings.voxelSize = float(args.number("--voxel-size", 0.0, 1e-30, 1e30));
    settings.levels = args.integer("--levels", 1, 1, 16);
    settings.maxVoxels = std::uint64_t(args.number("--max-voxels", double(settings.maxVoxels), 1.0, 1e15));
    settings.sdf = args.flag("--sdf");
    std::string fit = args.value("--blocker-fit", "plane-exact");
    if (fit == "projection") settings.blockerFit = BlockerFit::Projection;
    else if (fit != "plane-exact") throw InputError("--blocker-fit: expected plane-exact or projection, got '" + fit + "'");

    const std::string source = args.positional()[0];
    Scene scene = loadSceneArgument(source);
    ProgressBar bar;
    settings.progress = [&bar](float f) { bar.update(f); };
    SparseGeometryVolume volume = voxelizeScene(scene, settings);
    const VoxelizeStats& s = volume.stats();
    if (s.trianglesUsed == 0)
        throw InputError(source + ": no valid triangles to voxelize (" + std::to_string(s.skippedNonFinite) +
                         " non-finite, " + std::to_string(s.skippedDegenerate) + " degenerate skipped)");
    writeGeometryVolume(*out, volume);

    std::printf("voxelized %s: %zu triangles (%zu skipped: %zu non-finite, %zu degenerate) in %.3f s\n",
                source.c_str(), s.trianglesUsed, s.skippedNonFinite + s.skippedDegenerate, s.skippedNonFinite,
                s.skippedDegenerate, s.seconds);
    for (int l = 0; l < volume.levelCount(); ++l) {
        IndexBox b = volume.indexBounds(l);
        std::printf("  level %d: voxel %g, %llu active voxels, %zu bricks, index bbox [%d %d %d]..[%d %d %d]\n", l,
                    double(volume.voxelSize(l)), static_cast<unsigned long long>(volume.activeVoxelCount(l)),
                    volume.activeBricks(l).size(), b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z);
    }
    std::printf("wrote %s (%.1f MiB in memory)\n", out->c_str(), double(volume.memoryBytes()) / (1024.0 * 1024.0));
    return kOk;
}

}  // namespace

VOXGI_REGISTER_COMMAND("voxelize", kUsage, runVoxelize);

}  // namespace voxgi::cli
