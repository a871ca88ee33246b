// voxgi bench pathtrace: how fast the reference path tracer removes noise. For each scene, the
// error (RMSE of the beauty layer) that a fixed time buys against a cached high-spp reference,
// next to the rays per second the path tracer reaches. Time is the process's CPU time (all
// threads), so a busy machine changes the wall clock but not the figures.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <tbb/info.h>

#include "gi/metrics/image_metrics.h"
#include "gi/pathtrace/path_tracer.h"
#include "scenes/atomic_file.h"
#include "tools/args.h"
#include "tools/bench_registry.h"
#include "tools/embree_share.h"
#include "tools/eval_run.h"
#include "tools/scene_arg.h"
#include "volumes/openvdb_reference.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi bench pathtrace [--scenes cornell-box,sibenik,sponza] [--size 128] [--reference-spp 16384]\n"
    "       [--seconds 8] [--cache DIR] [--csv OUT.csv] [--unidirectional]\n"
    "  RMSE of the beauty layer against a cached --reference-spp render (another seed) after\n"
    "  --seconds/8, /4, /2 and --seconds of CPU time (all threads) of progressive rendering, and\n"
    "  rays per CPU second; then the path tracer's rays per CPU second against Embree's alone\n"
    "  (rtcIntersect1 / rtcOccluded1) on the very same rays.\n"
    "  --unidirectional: without the light-vertex connections (gi/pathtrace/light_paths.h).\n"
    "  --cache: reference cache (default $VOXGI_EVAL_CACHE, else out/eval-cache). Scenes whose\n"
    "  meshes are absent are skipped.";

void benchScene(const std::string& name, Scene scene, int size, int referenceSpp, double budget, bool lightPaths,
                const std::string& cache, std::ostringstream& csv) {
    scene.camera.width = scene.camera.height = size;
    std::printf("%s: %zu triangles, %dx%d, %d threads\n", name.c_str(), scene.triangleCount(), size, size,
                tbb::info::default_concurrency());
    std::fflush(stdout);
    const Reference reference = loadOrRenderReference(scene, name, referenceSpp, cache);
    std::printf("  reference: %d spp%s\n", referenceSpp, reference.fromCache ? " (cached)" : "");

    PathTracerOptions options;
    options.seed = 1;  // the reference uses seed 0: independent noise
    options.lightPaths = lightPaths;
    PathTracer tracer(scene, options);
    double elapsed = 0.0;
    for (double checkpoint : {budget / 8.0, budget / 4.0, budget / 2.0, budget}) {
        // Whole samples per pixel until the checkpoint: the last pass may overrun it a little,
        // and the time printed is the time spent.
        while (elapsed < checkpoint) {
            const double start = processCpuSeconds();
            tracer.render(1);
            elapsed += processCpuSeconds() - start;
        }
        const ImageMetrics m = computeMetrics(tracer.image(), reference.image, "beauty");
        const double raysPerSecond = double(tracer.raysTraced()) / elapsed;
        std::printf("  %6.2f CPU s  %5d spp  RMSE %.5f  relMSE %.5f  HDR-FLIP %.4f  %.2f M rays per CPU s\n", elapsed,
                    tracer.samplesPerPixel(), m.rmse, m.relMse, m.flip, raysPerSecond * 1e-6);
        csv << name << "," << size << "," << checkpoint << "," << elapsed << "," << tracer.samplesPerPixel() << ","
            << tracer.raysTraced() << "," << raysPerSecond * 1e-6 << "," << m.rmse << "," << m.relMse << "," << m.flip
            << "," << referenceSpp << "," << (lightPaths ? 1 : 0) << "\n";
        std::fflush(stdout);
    }
    const int n = std::max(1, tracer.samplesPerPixel() / 8);
    const EmbreeShare share = measureEmbreeShare(tracer, n);
    std::printf("  the same %.3g rays (%d spp): path tracer %.2f M rays per CPU s, Embree alone %.2f M: %.0f %%\n",
                share.rays, n, share.pathPerCpuS * 1e-6, share.barePerCpuS * 1e-6,
                100.0 * share.pathPerCpuS / share.barePerCpuS);
}

int runBench(const std::vector<std::string>& argv) {
    Args args(argv, {"--scenes", "--size", "--reference-spp", "--seconds", "--cache", "--csv"}, {"--unidirectional"});
    const bool lightPaths = !args.flag("--unidirectional");
    const std::vector<std::string> scenes = splitList(args.value("--scenes", "cornell-box,sibenik,sponza"));
    const int size = args.integer("--size", 128, 8, 8192);
    const int referenceSpp = args.integer("--reference-spp", 16384, 1, 1 << 24);
    const double budget = args.number("--seconds", 8.0, 0.01, 1e6);
    const char* env = std::getenv("VOXGI_EVAL_CACHE");
    const std::string cache = args.value("--cache", env ? env : "out/eval-cache");
    if (auto c = args.value("--csv")) requireWritable(*c, "--csv");

    std::ostringstream csv;
    csv << "scene,size,budget_cpu_s,cpu_s,spp,rays,mrays_per_cpu_s,rmse,relmse,flip,reference_spp,light_paths\n";
    for (const std::string& name : scenes) {
        std::optional<Scene> scene = loadBenchScene(name);
        if (!scene) continue;
        // A scene file is named by its stem: the name also names its cached reference.
        benchScene(std::filesystem::path(name).stem().string(), std::move(*scene), size, referenceSpp, budget, lightPaths,
                   cache, csv);
    }
    if (auto c = args.value("--csv")) {
        writeTextAtomically(*c, csv.str());
        std::printf("wrote %s\n", c->c_str());
    } else {
        std::printf("\n%s", csv.str().c_str());
    }
    return kOk;
}

}  // namespace

VOXGI_REGISTER_BENCHMARK("pathtrace", kUsage, runBench);

}  // namespace voxgi::cli
