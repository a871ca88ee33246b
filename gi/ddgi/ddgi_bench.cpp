// voxgi bench ddgi: probe rays per second against Embree's own throughput for the same rays
// (no shading), per-stage timings (trace, shade, blend, border, classify, sample), the update
// speed-up that probe culling gives.
#include "gi/ddgi/ddgi_bench.h"

#include <algorithm>
#include <cmath>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "gi/gbuffer_upload.h"
#include "gi/ddgi/ddgi_gpu.h"
#include "gi/ddgi/ddgi_system.h"
#include "gi/ddgi/volume_trace_bench.h"
#include "gi/ddgi/probe_sampling.h"
#include "gi/raytrace/ray_tracer.h"
#include "gl/resources.h"
#include "gl/timers.h"

namespace voxgi {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

double median(std::vector<double> v) { return gl::summarize(std::move(v)).median; }

// Medians of every stat of statList (ddgi_system.h) by name, over frames.
struct StageMedians {
    std::map<std::string, double> values;
    double operator[](const std::string& name) const {
        auto it = values.find(name);
        return it == values.end() ? 0.0 : it->second;
    }
    double update() const {
        const StageMedians& m = *this;
        return m["trace"] + m["shade"] + m["blend"] + m["border"] + m["classify"];
    }
};

StageMedians medianOf(const std::vector<std::map<std::string, double>>& frames) {
    std::map<std::string, std::vector<double>> all;
    for (const auto& frame : frames)
        for (const auto& [name, value] : frame) all[name].push_back(value);
    StageMedians m;
    for (const auto& [name, values] : all) m.values[name] = median(values);
    return m;
}

// "1.23 2.34" from /proc/loadavg: other builds share the two cores, so every table says how busy
// the machine was.
std::string loadAverage() {
    std::FILE* f = std::fopen("/proc/loadavg", "r");
    if (!f) return "?";
    double a = 0, b = 0, c = 0;
    int n = std::fscanf(f, "%lf %lf %lf", &a, &b, &c);
    std::fclose(f);
    if (n != 3) return "?";
    char text[64];
    std::snprintf(text, sizeof text, "%.2f %.2f %.2f", a, b, c);
    return text;
}

// One shading mode of the mode table: a hit-cache setting and a direct-light mode, traced and
// shaded with the probe gather (energy 1) and with direct light alone (energy 0).
struct ShadingMode {
    const char* name;
    DdgiHitCache cache;
    DdgiDirectLight direct;
    bool directOnlyRow;  // the energy-0 run differs from another mode's (not so for `probes`)
};

const ShadingMode kModes[] = {
    {"off, shadow rays", DdgiHitCache::Off, DdgiDirectLight::ShadowRays, true},
    {"probes, shadow rays", DdgiHitCache::Probes, DdgiDirectLight::ShadowRays, false},
    {"all, shadow rays", DdgiHitCache::All, DdgiDirectLight::ShadowRays, true},
    {"off, occlusion probes", DdgiHitCache::Off, DdgiDirectLight::OcclusionProbes, true},
    {"all, occlusion probes", DdgiHitCache::All, DdgiDirectLight::OcclusionProbes, true},
};

struct ModeRuns {
    std::unique_ptr<DdgiSystem> shade, direct;
    std::vector<double> traceRate, directRate, shadeRate, groups, evaluated, shadow;
};

StageMedians runFrames(DdgiSystem& ddgi, glm::vec3 eye, int frames, BlendBackend* backend) {
    std::vector<std::map<std::string, double>> all;
    for (int f = 0; f < frames; ++f) {
        all.emplace_back();
        for (const TechniqueStat& st : statList(ddgi.update(eye, backend))) all.back()[st.name] = st.value;
    }
    return medianOf(all);
}

// Embree alone: the same probe origins and directions (every probe, every ray of the last
// frame's set), intersected with nothing done at the hits, chunked like traceProbes. Best of
// `repeats`. With `hitRecord` each ray gets RayTracer::intersect's hit record (position,
// normals, uv), which any use of a hit needs, built the fastest way (intersectFan, per chunk,
// as traceProbes does); without, it is rtcIntersect1 and nothing else.
double rawEmbreeMs(const DdgiSystem& ddgi, int repeats, std::int64_t* rays, bool hitRecord = true) {
    const ProbeField& field = ddgi.field();
    const RaySet& set = ddgi.lastRays();
    const int probes = field.probeCount();
    const int stride = set.stride();
    *rays = std::int64_t(probes) * stride;
    double best = 1e30;
    for (int k = 0; k < repeats; ++k) {
        auto t0 = Clock::now();
        std::atomic<int> sink{0};
        constexpr int chunk = 64;
        const int chunks = (stride + chunk - 1) / chunk;
        tbb::parallel_for(tbb::blocked_range<int>(0, probes * chunks), [&](const tbb::blocked_range<int>& r) {
            int hits = 0;
            for (int task = r.begin(); task != r.end(); ++task) {
                int p = task / chunks, first = (task % chunks) * chunk, last = std::min(stride, first + chunk);
                glm::vec3 o = field.probePosition(p);
                if (hitRecord) {
                    RayHit records[chunk];
                    ddgi.tracer().intersectFan(o, &set.directions[std::size_t(first)], last - first, records);
                    for (int i = 0; i < last - first; ++i) hits += records[i].hit;
                    continue;
                }
                for (int i = first; i < last; ++i)
                    hits += std::isfinite(ddgi.tracer().nearestHit(o, set.directions[std::size_t(i)]));
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
    const RaySet& rays = ddgi.lastRays();
    for (std::size_t i = 0; i < trace.surfels.size(); ++i) {
        const ProbeSurfel& s = trace.surfels[i];
        const int probe = int(i / std::size_t(trace.stride)), ray = int(i % std::size_t(trace.stride));
        if (trace.work[std::size_t(probe)] == ProbeWork::Full && s.distance > 0.0f && s.distance < kMissDistance)
            pts.emplace_back(trace.position(rays, probe, ray), s.normal);
    }
    if (pts.size() > 200000) pts.resize(200000);
    *points = int(pts.size());
    if (pts.empty()) return 0.0;
    auto t0 = Clock::now();
    const ProbeSampler sampler(ddgi.field());
    std::atomic<float> sink{0.0f};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pts.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        float acc = 0.0f;
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            acc += sampler.irradiance(pts[i].first, pts[i].second, pts[i].second).x;
        sink = sink + acc;
    });
    return msSince(t0) * 1e6 / double(pts.size());
}

// GL apply over a width x height G-buffer of probe-ray hits: median wall time of `frames`
// (glFinish) after three untimed ones (drivers compile lazily), and the median GPU time.
double glApplyMs(DdgiSystem& ddgi, int width, int height, int frames, double* gpuMs) {
    const ProbeTrace& trace = ddgi.lastTrace();
    std::vector<glm::vec4> pos(std::size_t(width * height), glm::vec4(0.0f)), nrm(pos.size()), alb(pos.size(), glm::vec4(0.7f, 0.7f, 0.7f, 0.0f)),
        emi(pos.size(), glm::vec4(0.0f));
    std::size_t k = 0;
    for (std::size_t i = 0; i < trace.surfels.size() && k < pos.size(); ++i) {
        const ProbeSurfel& s = trace.surfels[i];
        const int probe = int(i / std::size_t(trace.stride)), ray = int(i % std::size_t(trace.stride));
        if (trace.work[std::size_t(probe)] == ProbeWork::None || s.distance <= 0.0f || s.distance >= kMissDistance) continue;
        pos[k] = glm::vec4(trace.position(ddgi.lastRays(), probe, ray), 1.0f);
        nrm[k++] = glm::vec4(s.normal, 1.0f);
    }
    UploadedGBuffer g = uploadGBuffer(pos, nrm, alb, emi, width, height, ddgi.tracer().scene().camera.eye);
    DdgiGpu gpu(ddgi.field());
    gl::Handle query = gl::createTimerQuery();
    std::vector<double> ms, gpuTimes;
    for (int f = 0; f < frames + 3; ++f) {
        glFinish();
        auto t0 = Clock::now();
        glBeginQuery(GL_TIME_ELAPSED, query.id());
        gpu.apply(ddgi.field(), g.view);
        glEndQuery(GL_TIME_ELAPSED);
        glFinish();
        if (f < 3) continue;
        ms.push_back(msSince(t0));
        gpuTimes.push_back(gl::timerQueryMs(query.id()));
    }
    *gpuMs = median(gpuTimes);
    return median(ms);
}

void benchScene(const std::string& path, Scene scene, const BenchRequest& request) {
    // The benchmark's grid unless the scene or --set gives one.
    if (!scene.gi.has("ddgi.probes")) scene.gi.set("ddgi.probes", "16,8,12");
    if (!scene.gi.has("ddgi.rays")) scene.gi.set("ddgi.rays", "256");
    const int frames = request.frames > 0 ? request.frames : 5;
    const int warmup = request.warmup > 0 ? request.warmup : 12;
    const glm::vec3 eye = scene.camera.eye;

    const std::string loadBefore = loadAverage();
    auto t0 = Clock::now();
    RayTracer tracer(scene);
    double bvhMs = msSince(t0);
    DdgiDesc desc = readDdgiDesc(scene.gi);
    desc.backend = Backend::Cpu;

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
    std::vector<double> raw, bare;
    std::int64_t rawRays = 0;
    for (int i = 0; i < frames; ++i) {
        fs.push_back(runFrames(full, eye, 1, nullptr));
        raw.push_back(rawEmbreeMs(full, 1, &rawRays));
        bare.push_back(rawEmbreeMs(full, 1, &rawRays, false));
        cs.push_back(runFrames(culled, eye, 1, nullptr));
    }
    auto med = [](const std::vector<StageMedians>& v) {
        std::vector<std::map<std::string, double>> frames;
        for (const StageMedians& m : v) frames.push_back(m.values);
        return medianOf(frames);
    };
    StageMedians f = med(fs), c = med(cs);
    double rawMs = median(raw);
    double rawRate = double(rawRays) / (rawMs * 1e-3);
    double ddgiRate = f["rays_traced"] / ((f["trace"] + f["shade"]) * 1e-3);
    double traceRate = f["rays_traced"] / (f["trace"] * 1e-3);
    ProbeStateCounts states = countStates(culled.field());

    // The mode table: every hit-cache and direct-light mode on the same rays, culling off,
    // frames interleaved with Embree alone so that load hits all alike.
    std::vector<ModeRuns> modes;
    for (const ShadingMode& m : kModes) {
        DdgiDesc md = all;
        md.hitCache = m.cache;
        md.directLight = m.direct;
        ModeRuns runs;
        runs.shade = std::make_unique<DdgiSystem>(tracer, md);
        if (m.directOnlyRow) {
            md.energyPreservation = 0.0f;
            runs.direct = std::make_unique<DdgiSystem>(tracer, md);
        }
        modes.push_back(std::move(runs));
    }
    for (ModeRuns& m : modes) {
        runFrames(*m.shade, eye, warmup, nullptr);
        if (m.direct) runFrames(*m.direct, eye, warmup, nullptr);
    }
    // Each update is paired with an Embree-alone pass just before it; the ratio of the two
    // rates is taken per frame (load drifts over seconds, less within a pair).
    auto rawRateNow = [&] {
        std::int64_t n = 0;
        double ms = rawEmbreeMs(full, 1, &n);
        return double(n) / (ms * 1e-3);
    };
    std::vector<double> modeRaw;
    for (int i = 0; i < frames; ++i) {
        for (ModeRuns& m : modes) {
            double raw = rawRateNow();
            modeRaw.push_back(raw);
            DdgiFrameStats st = m.shade->update(eye, nullptr);
            m.traceRate.push_back(double(st.raysTraced) / (st.traceMs * 1e-3) / raw);
            m.shadeRate.push_back(double(st.raysTraced) / ((st.traceMs + st.shadeMs) * 1e-3) / raw);
            m.groups.push_back(double(st.cacheGroups));
            m.evaluated.push_back(double(st.cacheGroupsEvaluated));
            m.shadow.push_back(double(st.shadowQueries));
            if (m.direct) {
                raw = rawRateNow();
                DdgiFrameStats sd = m.direct->update(eye, nullptr);
                m.directRate.push_back(double(sd.raysTraced) / ((sd.traceMs + sd.shadeMs) * 1e-3) / raw);
            }
        }
    }
    const std::string loadAfter = loadAverage();
    double modeRawRate = median(modeRaw);

    int points = 0;
    double sampleNs = sampleNsPerPoint(full, &points);

    std::printf("Embree alone (same rays, no shading): %.2f Mrays/s (%lld rays in %.1f ms, median)\n", rawRate * 1e-6,
                (long long)rawRays, rawMs);
    std::printf("  (rtcIntersect1 with no hit record:  %.2f Mrays/s; the hit record takes %.0f %% of Embree alone's time)\n",
                double(rawRays) / (median(bare) * 1e-3) * 1e-6, 100.0 * (1.0 - median(bare) / rawMs));
    std::printf("DDGI trace only:                      %.2f Mrays/s\n", traceRate * 1e-6);
    std::printf("DDGI trace + shade:                   %.2f Mrays/s = %.0f %% of Embree alone (goal >= 70 %%; hit_cache %s),\n"
                "                                      %.0f %% of rtcIntersect1 with no hit record\n",
                ddgiRate * 1e-6, 100.0 * ddgiRate / rawRate,
                desc.hitCache == DdgiHitCache::Off ? "off" : desc.hitCache == DdgiHitCache::Probes ? "probes" : "all",
                100.0 * ddgiRate * median(bare) * 1e-3 / double(rawRays));
    std::printf("modes, %% of Embree alone (median %.2f Mrays/s, timed just before each update), medians of %d frames,\n"
                "load average %s before, %s after:\n",
                modeRawRate * 1e-6, frames, loadBefore.c_str(), loadAfter.c_str());
    std::printf("  %-24s %8s %15s %14s %20s %14s\n", "hit_cache, direct", "trace", "trace + direct", "trace + shade",
                "groups (evaluated)", "light tests");
    for (std::size_t i = 0; i < modes.size(); ++i) {
        const ModeRuns& m = modes[i];
        char direct[32] = "(as above)";
        if (m.direct) std::snprintf(direct, sizeof direct, "%.0f %%", 100.0 * median(m.directRate));
        char groups[48];
        std::snprintf(groups, sizeof groups, "%.0f (%.0f)", median(m.groups), median(m.evaluated));
        std::printf("  %-24s %6.0f %% %15s %12.0f %% %20s %14.0f\n", kModes[i].name,
                    100.0 * median(m.traceRate), direct, 100.0 * median(m.shadeRate), groups, median(m.shadow));
    }
    std::printf("stage medians over %d frames [ms]      culling off   culling on\n", frames);
    auto row = [&](const char* name, double a, double b) { std::printf("  %-36s %10.2f %12.2f\n", name, a, b); };
    row("trace (hit-cache grouping included)", f["trace"], c["trace"]);
    row("shade (direct + previous probes)", f["shade"], c["shade"]);
    row("  of which merge hit-cache tables", f["shade_merge"], c["shade_merge"]);
    row("  of which evaluate cache groups", f["shade_groups"], c["shade_groups"]);
    row("  of which shade every hit", f["shade_hits"], c["shade_hits"]);
    row("blend (CPU reference)", f["blend"], c["blend"]);
    row("border (CPU reference)", f["border"], c["border"]);
    row("classify + relocate", f["classify"], c["classify"]);
    row("update total", f.update(), c.update());
    std::printf("  rays per frame                        %10.0f %12.0f\n", f["rays_traced"], c["rays_traced"]);
    std::printf("culling: %d active, %d sleeping, %d off -> update speed-up %.2fx\n", states.active, states.sleeping,
                states.off, f.update() / std::max(c.update(), 1e-9));
    std::printf("sample (CPU reference): %.0f ns per shading point over %d points\n", sampleNs, points);

    if (request.gl) {
        DdgiSystem gpuSystem(tracer, all);
        DdgiGpu backend(gpuSystem.field());
        runFrames(gpuSystem, eye, 2, &backend);
        std::vector<StageMedians> frameStages;
        std::vector<double> upload, blendGpu, borderGpu, readback;
        for (int i = 0; i < std::min(frames, 5); ++i) {
            frameStages.push_back(runFrames(gpuSystem, eye, 1, &backend));
            const DdgiGpu::Times& t = backend.lastTimes();
            upload.push_back(t.uploadMs);
            blendGpu.push_back(t.blendGpuMs);
            borderGpu.push_back(t.borderGpuMs);
            readback.push_back(t.readbackMs);
        }
        StageMedians g = med(frameStages);
        double applyGpu = 0.0;
        const double applyWall = glApplyMs(gpuSystem, 512, 512, 10, &applyGpu);
        std::printf("GL (%s), medians, culling off:\n", request.device.c_str());
        std::printf("  blend %.2f ms wall: uploads %.2f ms (atlases, shaded rays), kernels %.3f ms GPU\n", g["blend"],
                    median(upload), median(blendGpu));
        std::printf("  border + readback %.2f ms wall: kernels %.3f ms GPU, readback %.2f ms\n", g["border"],
                    median(borderGpu), median(readback));
        std::printf("  sample (apply pass, 512x512 G-buffer) %.2f ms wall, %.3f ms GPU\n", applyWall, applyGpu);
        printVolumeTraceBench(gpuSystem);
        printVolumeUpdateBench(tracer, all, eye, std::min(frames, 5));
    }
}

}  // namespace

void runDdgiBench(const BenchRequest& request) {
    std::printf("voxgi bench ddgi: %d threads\n", request.threads);
    if (!request.gl) std::printf("(no GL context: GL stages skipped)\n");
    for (const auto& [name, scene] : request.scenes) benchScene(name, scene, request);
}

}  // namespace voxgi
