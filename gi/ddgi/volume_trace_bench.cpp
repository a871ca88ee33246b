#include "gi/ddgi/volume_trace_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

#include "gi/ddgi/ddgi_gpu.h"
#include "gi/ddgi/ddgi_system.h"
#include "gi/ddgi/occupancy_query.h"
#include "gi/ddgi/volume_trace_gpu.h"
#include "gi/raytrace/ray_tracer.h"
#include "gi/raytrace/triangle_bvh.h"
#include "volumes/geometry_volume.h"
#include "volumes/nano_geometry.h"

namespace voxgi {

namespace {

// Median of three traces of `rays`: "kernel G ms GPU, W ms wall, R Mrays/s (wall)".
std::string timeTraces(VolumeTracerGl& tracer, const std::vector<VolumeRay>& rays) {
    std::vector<double> gpu, wall;
    for (int k = 0; k < 3; ++k) {
        tracer.trace(rays, kMissDistance);
        gpu.push_back(tracer.lastKernelMs());
        wall.push_back(tracer.lastKernelWallMs());
    }
    std::sort(gpu.begin(), gpu.end());
    std::sort(wall.begin(), wall.end());
    char line[160];
    std::snprintf(line, sizeof line, "kernel %.2f ms GPU, %.2f ms wall, %.1f Mrays/s (wall)", gpu[1], wall[1],
                  double(rays.size()) / wall[1] * 1e-3);
    return line;
}

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void printVolumeTraceBench(const DdgiSystem& ddgi) {
    const ProbeField& field = ddgi.field();
    const RaySet& set = ddgi.lastRays();
    std::vector<VolumeRay> rays;
    rays.reserve(std::size_t(field.probeCount()) * std::size_t(set.stride()));
    for (int p = 0; p < field.probeCount(); ++p)
        for (const glm::vec3& d : set.directions) rays.push_back({field.probePosition(p), 1e30f, d, 0.0f});
    const float spacing = field.smallestSpacing();
    std::printf("GL probe rays through the NanoVDB geometry volume (%zu rays, every probe's; kernel only):\n",
                rays.size());
    for (int perSpacing : {4, 8, 16}) {
        VoxelizeSettings settings;
        settings.voxelSize = spacing / float(perSpacing);
        const auto t0 = std::chrono::steady_clock::now();
        const SparseGeometryVolume volume = voxelizeScene(ddgi.tracer().scene(), settings);
        const NanoGeometry nano = makeNanoGeometry(volume);
        const double buildMs = msSince(t0);
        VolumeTracerGl tracer(nano);
        std::printf("  voxel = spacing/%-2d (%.4g): %llu voxels, %.1f MiB NanoVDB, built in %.0f ms; %s\n", perSpacing,
                    double(settings.voxelSize), static_cast<unsigned long long>(nano.activeVoxels),
                    double(nano.bytes()) / (1 << 20), buildMs, timeTraces(tracer, rays).c_str());
    }
    // The same rays through the triangles (ddgi.trace = bvh).
    const auto t0 = std::chrono::steady_clock::now();
    const TriangleBvh bvh = buildTriangleBvh(ddgi.tracer().scene());
    const double buildMs = msSince(t0);
    VolumeTracerGl tracer(ddgi.tracer().scene(), bvh);
    std::printf("  triangles' BVH: %zu triangles, %zu nodes, %.1f MiB with the surfaces, built in %.0f ms; %s\n",
                bvh.triangle.size(), bvh.nodeCount(), double(bvh.bytes() + bvh.triangle.size() * 64) / (1 << 20), buildMs,
                timeTraces(tracer, rays).c_str());
}

void printVolumeUpdateBench(const RayTracer& tracer, DdgiDesc desc, glm::vec3 eye, int frames) {
    desc.backend = Backend::Gl;
    std::printf("GL update with ddgi.trace = volume, and bvh (medians of %d frames; wall ms unless GPU):\n", frames);
    auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v.empty() ? 0.0 : v[v.size() / 2];
    };
    // The fourth row without classification: every probe traces and blends every frame. The last
    // traces the triangles (its fixed rays through the volume at 8 voxels per spacing).
    struct Run {
        int perSpacing;
        bool classify;
        DdgiTrace trace;
    };
    const Run runs[] = {{4, true, DdgiTrace::Volume},
                        {8, true, DdgiTrace::Volume},
                        {16, true, DdgiTrace::Volume},
                        {16, false, DdgiTrace::Volume},
                        {8, true, DdgiTrace::Bvh}};
    for (const auto& [perSpacing, classify, through] : runs) {
        desc.traceVoxels = perSpacing;
        desc.classify = classify;
        desc.trace = through;
        DdgiSystem system(tracer, desc);
        DdgiGpu gpu(system.field());
        const auto t0 = std::chrono::steady_clock::now();
        const bool triangles = through == DdgiTrace::Bvh;
        gpu.traceOnGpu(tracer, system.field(), through);
        gpu.waitForEachStage(true);  // per-stage wall and GPU times, this update's ray counts
        const double buildMs = msSince(t0);
        std::vector<double> total, trace, blend, border, classes, gpuTrace, gpuBlend, gpuBorder, gpuClassify, rays;
        for (int f = 0; f < frames + 2; ++f) {
            const DdgiFrameStats s = system.update(eye, &gpu);
            if (f < 2) continue;
            total.push_back(s.traceMs + s.shadeMs + s.blendMs + s.borderMs + s.classifyMs);
            trace.push_back(s.traceMs);
            blend.push_back(s.blendMs);
            border.push_back(s.borderMs);
            classes.push_back(s.classifyMs);
            rays.push_back(double(s.raysTraced));
            const DdgiGpu::Times& t = gpu.lastTimes();
            gpuTrace.push_back(t.shadeGpuMs);
            gpuBlend.push_back(t.blendGpuMs);
            gpuBorder.push_back(t.borderGpuMs);
            gpuClassify.push_back(t.classifyGpuMs);
        }
        std::printf("  %strace_voxels %-2d%s: %s built in %.0f ms; update %.2f: trace + shade %.2f, blend %.2f, "
                    "border %.2f, schedule + classify %.2f (GPU %.3f / %.3f / %.3f / %.3f); %.0f rays\n",
                    triangles ? "bvh, " : "", perSpacing, classify ? "" : ", classify off",
                    triangles ? "volume and BVH" : "volume", buildMs, median(total), median(trace), median(blend), median(border), median(classes),
                    median(gpuTrace), median(gpuBlend), median(gpuBorder), median(gpuClassify), median(rays));
    }
}

}  // namespace voxgi
