// voxgi bench ddgi: probe rays per second against Embree's own throughput for the same rays
// (no shading), per-stage timings (trace, shade, blend, border, classify, sample), the update
// speed-up that probe culling gives, for the Cornell box and Sibenik by default.
#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "gi/gbuffer_upload.h"
#include "gi/ddgi/ddgi_gpu.h"
#include "gi/ddgi/ddgi_system.h"
#include "gi/ddgi/probe_sampling.h"
#include "gi/raytrace/ray_tracer.h"
#include "render/gl/context.h"
#include "scenes/errors.h"
#include "scenes/scene_loader.h"
#include "tools/bench_registry.h"
#include "tools/scene_arg.h"

namespace voxgi::cli {

namespace {

const char* kUsage =
    "voxgi bench ddgi [SCENE...] [--probes X,Y,Z] [--rays N] [--frames N] [--warmup N] [--threads N] [--set k=v]...\n"
    "  SCENE: default cornell-box and ../shared/scenes/sibenik/sibenik.obj; 16x8x12 probes, 256 rays, 2 threads";

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct StageMedians {
    double trace = 0, shade = 0, blend = 0, border = 0, classify = 0;
    double rays = 0;     // rays traced per frame (median)
    double update() const { return trace + shade + blend + border + classify; }
};

StageMedians runFrames(DdgiSystem& ddgi, glm::vec3 eye, int frames, BlendBackend* backend) {
    std::vector<double> t, s, b, bo, c, r;
    for (int f = 0; f < frames; ++f) {
        DdgiFrameStats st = ddgi.update(eye, backend);
        t.push_back(st.traceMs);
        s.push_back(st.shadeMs);
        b.push_back(st.blendMs);
        bo.push_back(st.borderMs);
        c.push_back(st.classifyMs);
        r.push_back(double(st.raysTraced));
    }
    return {median(t), median(s), median(b), median(bo), median(c), median(r)};
}

// Embree alone: the same probe origins and directions (every probe, every ray of the last
// frame's set), intersected with nothing done at the hits, chunked like traceProbes. Best of
// `repeats`.
double rawEmbreeMs(const DdgiSystem& ddgi, int repeats, std::int64_t* rays) {
    const ProbeField& field = ddgi.field();
    const RaySet& set = ddgi.lastRays();
    const int probes = field.probeCount();
    const int stride = set.stride();
    *rays = std::int64_t(probes) * stride;
    double best = 1e30;
    for (int k = 0; k < repeats; ++k) {
        auto t0 = Clock::now();
        std::atomic<int> sink{0};
        const int chunk = 64, chunks = (stride + chunk - 1) / chunk;
        tbb::parallel_for(tbb::blocked_range<int>(0, probes * chunks), [&](const tbb::blocked_range<int>& r) {
            int hits = 0;
            for (int task = r.begin(); task != r.end(); ++task) {
                int p = task / chunks, first = (task % chunks) * chunk, last = std::min(stride, first + chunk);
                glm::vec3 o = field.probePosition(p);
                for (int i = first; i < last; ++i) hits += ddgi.tracer().intersect(o, set.directions[std::size_t(i)]).hit;
            }
            sink += hits;
        });
        best = std::min(best, msSince(t0));
    }
    return best;
}

// CPU sampling cost per shading point, over points on probe-ray hits.
double sampleNsPerPoint(const DdgiSystem& ddgi, int* points) {
    const ProbeTrace& trace = ddgi.lastTrace();
    std::vector<std::pair<glm::vec3, glm::vec3>> pts;
    for (const Surfel& s : trace.surfels)
        if (s.distance > 0.0f && s.distance < kMissDistance) pts.emplace_back(s.position, s.normal);
    if (pts.size() > 200000) pts.resize(200000);
    *points = int(pts.size());
    if (pts.empty()) return 0.0;
    auto t0 = Clock::now();
    std::atomic<float> sink{0.0f};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pts.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        float acc = 0.0f;
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            acc += sampleIrradiance(ddgi.field(), pts[i].first, pts[i].second, pts[i].second).x;
        sink = sink + acc;
    });
    return msSince(t0) * 1e6 / double(pts.size());
}

// GL apply over a width x height G-buffer of probe-ray hits; median of `frames` (glFinish).
double glApplyMs(DdgiSystem& ddgi, int width, int height, int frames) {
    const ProbeTrace& trace = ddgi.lastTrace();
    std::vector<glm::vec4> pos(std::size_t(width * height), glm::vec4(0.0f)), nrm(pos.size()), alb(pos.size(), glm::vec4(0.7f, 0.7f, 0.7f, 0.0f)),
        emi(pos.size(), glm::vec4(0.0f));
    std::size_t k = 0;
    for (const Surfel& s : trace.surfels) {
        if (k == pos.size()) break;
        if (s.distance <= 0.0f || s.distance >= kMissDistance) continue;
        pos[k] = glm::vec4(s.position, 1.0f);
        nrm[k++] = glm::vec4(s.normal, 1.0f);
    }
    UploadedGBuffer g = uploadGBuffer(pos, nrm, alb, emi, width, height, ddgi.tracer().scene().camera.eye);
    DdgiGpu gpu(ddgi.field());
    std::vector<double> ms;
    for (int f = 0; f < frames; ++f) {
        glFinish();
        auto t0 = Clock::now();
        gpu.apply(ddgi.field(), g.view);
        glFinish();
        ms.push_back(msSince(t0));
    }
    return median(ms);
}

void benchScene(const std::string& path, const Args& args, gl::Context* context) {
    Scene scene = loadSceneArgument(path);
    scene.gi.set("ddgi.probes", args.value("--probes", "16,8,12"));
    scene.gi.set("ddgi.rays", std::to_string(args.integer("--rays", 256, 1, 4096)));
    for (const std::string& s : args.values("--set")) scene.gi.applyOverride(s);
    const int frames = args.integer("--frames", 5, 1, 1000);
    const int warmup = args.integer("--warmup", 12, 0, 1000);
    const glm::vec3 eye = scene.camera.eye;

    auto t0 = Clock::now();
    RayTracer tracer(scene);
    double bvhMs = msSince(t0);
    DdgiDesc desc = readDdgiDesc(scene.gi);
    desc.gpuBlend = false;

    std::printf("\n== %s: %zu triangles (BVH %.0f ms), %d lights, probes %dx%dx%d, %d+%d rays/probe\n", path.c_str(),
                tracer.triangleCount(), bvhMs, int(scene.lights.size()), desc.probeCounts.x, desc.probeCounts.y,
                desc.probeCounts.z, desc.rays, desc.fixedRayCount());

    // Culling off (every probe traces and blends every frame) against culling on
    // (classification: sleeping and off probes), frames interleaved so that load from other
    // processes hits both alike.
    DdgiDesc all = desc;
    all.classify = false;
    DdgiSystem full(tracer, all), culled(tracer, desc);
    runFrames(full, eye, warmup, nullptr);
    runFrames(culled, eye, warmup, nullptr);
    std::vector<StageMedians> fs, cs;
    std::vector<double> raw;
    std::int64_t rawRays = 0;
    for (int i = 0; i < frames; ++i) {
        fs.push_back(runFrames(full, eye, 1, nullptr));
        raw.push_back(rawEmbreeMs(full, 1, &rawRays));
        cs.push_back(runFrames(culled, eye, 1, nullptr));
    }
    auto med = [](const std::vector<StageMedians>& v) {
        auto pick = [&](double StageMedians::*m) {
            std::vector<double> x;
            for (const StageMedians& s : v) x.push_back(s.*m);
            return median(x);
        };
        return StageMedians{pick(&StageMedians::trace), pick(&StageMedians::shade), pick(&StageMedians::blend),
                            pick(&StageMedians::border), pick(&StageMedians::classify), pick(&StageMedians::rays)};
    };
    StageMedians f = med(fs), c = med(cs);
    double rawMs = median(raw);
    double rawRate = double(rawRays) / (rawMs * 1e-3);
    double ddgiRate = f.rays / ((f.trace + f.shade) * 1e-3);
    double traceRate = f.rays / (f.trace * 1e-3);
    ProbeStateCounts states = countStates(culled.field());

    // The same without the probe gather at hits (energy 0): what direct light alone costs.
    DdgiDesc direct = all;
    direct.energyPreservation = 0.0f;
    DdgiSystem directOnly(tracer, direct);
    runFrames(directOnly, eye, 1, nullptr);
    StageMedians d = runFrames(directOnly, eye, frames, nullptr);
    double directRate = d.rays / ((d.trace + d.shade) * 1e-3);

    int points = 0;
    double sampleNs = sampleNsPerPoint(full, &points);

    std::printf("Embree alone (same rays, no shading): %.2f Mrays/s (%lld rays in %.1f ms, median)\n", rawRate * 1e-6,
                (long long)rawRays, rawMs);
    std::printf("DDGI trace only:                      %.2f Mrays/s\n", traceRate * 1e-6);
    std::printf("DDGI trace + shade:                   %.2f Mrays/s = %.0f %% of Embree alone (goal >= 70 %%)\n",
                ddgiRate * 1e-6, 100.0 * ddgiRate / rawRate);
    std::printf("DDGI trace + direct light only:       %.2f Mrays/s = %.0f %% (shade %.2f ms; the probe gather is the rest)\n",
                directRate * 1e-6, 100.0 * directRate / rawRate, d.shade);
    std::printf("stage medians over %d frames [ms]      culling off   culling on\n", frames);
    auto row = [&](const char* name, double a, double b) { std::printf("  %-36s %10.2f %12.2f\n", name, a, b); };
    row("trace", f.trace, c.trace);
    row("shade (direct + previous probes)", f.shade, c.shade);
    row("blend (CPU reference)", f.blend, c.blend);
    row("border (CPU reference)", f.border, c.border);
    row("classify + relocate", f.classify, c.classify);
    row("update total", f.update(), c.update());
    std::printf("  rays per frame                        %10.0f %12.0f\n", f.rays, c.rays);
    std::printf("culling: %d active, %d sleeping, %d off -> update speed-up %.2fx\n", states.active, states.sleeping,
                states.off, f.update() / std::max(c.update(), 1e-9));
    std::printf("sample (CPU reference): %.0f ns per shading point over %d points\n", sampleNs, points);

    if (context) {
        DdgiSystem gpuSystem(tracer, all);
        DdgiGpu backend(gpuSystem.field());
        runFrames(gpuSystem, eye, 2, &backend);
        StageMedians g = runFrames(gpuSystem, eye, std::min(frames, 3), &backend);
        std::printf("GL (%s):\n", context->description().c_str());
        std::printf("  blend %.2f ms, border + readback %.2f ms (culling off)\n", g.blend, g.border);
        std::printf("  sample (apply pass, 512x512 G-buffer) %.2f ms\n", glApplyMs(gpuSystem, 512, 512, 3));
    }
}

int runBenchDdgi(const std::vector<std::string>& argv) {
    Args args(argv, {"--probes", "--rays", "--frames", "--warmup", "--threads", "--set"}, {"--no-gl"}, {"--set"});
    int threads = args.integer("--threads", 2, 1, 1024);
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    std::vector<std::string> scenes = args.positional();
    if (scenes.empty()) {
        scenes.push_back("cornell-box");
        const char* env = std::getenv("VOXGI_SCENES");
        std::filesystem::path shared = env ? std::filesystem::path(env)
                                           : std::filesystem::path(builtinScenePath("cornell-box")).parent_path().parent_path() /
                                                 ".." / "shared" / "scenes";
        std::string sibenik = (shared / "sibenik" / "sibenik.obj").string();
        if (std::filesystem::exists(sibenik)) scenes.push_back(sibenik);
        else std::printf("(sibenik not found at %s; skipped)\n", sibenik.c_str());
    }
    std::unique_ptr<gl::Context> context;
    if (!args.flag("--no-gl")) {
        try {
            context = gl::Context::createHeadless();
        } catch (const gl::GlError& e) {
            std::printf("(no GL context: %s; GL stages skipped)\n", e.what());
        }
    }
    std::printf("voxgi bench ddgi: %d threads\n", threads);
    for (const std::string& s : scenes) benchScene(s, args, context.get());
    return kOk;
}

}  // namespace

VOXGI_REGISTER_BENCHMARK("ddgi", kUsage, runBenchDdgi);

}  // namespace voxgi::cli
