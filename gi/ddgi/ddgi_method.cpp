// The `ddgi` method as the tools see it: settings, plan, presets, views, stiff cases, benchmark.
#include <cmath>
#include <sstream>

#include "gi/ddgi/ddgi_bench.h"
#include "gi/ddgi/ddgi_debug_views.h"
#include "gi/ddgi/ddgi_technique.h"
#include "gi/method.h"
#include "gi/sky/sky_volume.h"

namespace voxgi {

namespace {

TechniquePlan ddgiPlan(const Scene& scene) {
    const DdgiDesc d = readDdgiDesc(scene.gi);
    int probes = 0;
    std::ostringstream grids;  // "8x4x5 at 4.6 m", one per volume
    grids.precision(3);
    const char* separator = "";
    for (const ProbeVolume& v : layoutVolumes(d, scene.bounds(), scene.camera.eye)) {
        probes += v.probeCount();
        grids << separator << v.counts.x << "x" << v.counts.y << "x" << v.counts.z
              << " at " << v.minSpacing() << " m";
        separator = ", ";
    }
    TechniquePlan p;
    p.update.push_back({kDdgiTraceStage, std::to_string(probes) + " probes (" + grids.str() + ") x " + std::to_string(d.rays) +
                                          " rays (+" + std::to_string(d.fixedRayCount()) + " fixed) " +
                                          (d.trace == DdgiTrace::Triangles ? "with Embree"
                                           : d.trace == DdgiTrace::Volume  ? "through the NanoVDB volume on gl"
                                                                           : "through the triangles' BVH on gl (fixed rays "
                                                                             "through the NanoVDB volume)")});
    p.update.push_back({kDdgiShadeStage, std::string("emission, direct light by ") +
                                          (d.directLight == DdgiDirectLight::ShadowRays ? "shadow rays" : "occlusion probes") +
                                          (scene.sky.enabled && readSkyVolumeDesc(scene.gi).light ? ", the sky volume's irradiance" : "") +
                                          " and the previous field's irradiance at every hit"});
    const std::string where = d.gpuBlend() ? "gl" : "cpu";
    p.update.push_back({kDdgiBlendStage, "irradiance and distance atlases on " + where});
    p.update.push_back({kDdgiBorderStage, "atlas tile borders on " + where});
    p.update.push_back({kDdgiClassifyStage, std::string(d.relocate ? "relocate and " : "") + "classify the probes"});
    p.apply.push_back({"ddgi.sample", "irradiance from the probe field at every pixel"});
    if (d.classify)
        p.notes.push_back("ddgi: sleeping probes trace all rays every " + std::to_string(d.sleepInterval) +
                          " frames, off probes only their fixed rays");
    return p;
}

SettingList quick(SettingList s) {
    s.push_back({"ddgi.rays", "64"});
    return s;
}

std::vector<StressCase> ddgiStressCases() {
    StressCase walls;
    walls.name = "probes-in-walls";
    walls.description = "3x3x3 probes spaced half the box: 26 of 27 lie in the walls";
    walls.frames = 8;
    walls.settings = [](const Scene& scene) {
        glm::vec3 h = 0.5f * scene.bounds().extent();
        std::ostringstream spacing;
        spacing << h.x << "," << h.y << "," << h.z;
        return quick({{"ddgi.probes", "3,3,3"}, {"ddgi.spacing", spacing.str()}});
    };
    std::vector<StressCase> cases{walls};
    for (const char* h : {"0", "1"}) {
        StressCase c;
        c.name = std::string("hysteresis-") + h;
        c.description = std::string("Cornell box, ddgi.hysteresis = ") + h;
        c.frames = 8;
        c.settings = [h](const Scene&) { return quick({{"ddgi.hysteresis", h}}); };
        cases.push_back(c);
    }
    return cases;
}

}  // namespace

MethodInfo ddgiMethod() {
    MethodInfo m;
    m.name = "ddgi";
    m.summary = "dynamic diffuse GI: probe fields traced with Embree, blended on the GPU (seed 004, RTXGI)";
    declareSettings(m, ddgiSettings());
    m.memoryBytes = [](const GiSettings& gi) {
        // Peak resident memory measured on the Cornell box (CPU tracing, GL atlases in host
        // memory on llvmpipe), 4^3 to 16^3 probes: about 40 bytes per atlas texel (the CPU
        // atlases, their upload rows and the GL textures, 16 bytes each) and 110 bytes per ray
        // (its direction, hit record and shaded surfel). Fitted grids have at most fit_cells
        // probes per axis per cascade.
        const DdgiDesc d = readDdgiDesc(gi);
        const glm::dvec3 counts = d.probeCounts.x > 0 ? glm::dvec3(d.probeCounts) : glm::dvec3(d.fitCells);
        const double probes = counts.x * counts.y * counts.z * double(d.cascades);
        const double texels = std::pow(d.irradianceTexels + 2.0, 2.0) + std::pow(d.distanceTexels + 2.0, 2.0);
        return probes * (40.0 * texels + 110.0 * double(d.raysPerProbe()));
    };
    m.create = [](const Scene& s) { return std::make_unique<DdgiTechnique>(s); };
    m.plan = ddgiPlan;
    // Grids fitted to the scene's shape (cubic cells): fixed counts per axis gave Sponza's
    // 37 x 16 x 23 m 4x4x4 probes 9.3 x 3.9 x 5.7 m apart, none in the sunlit courtyard
    // (docs/ddgi.md, "Fitted grids").
    m.presets = {{"low", {{"ddgi.rays", "64"}, {"ddgi.fit_cells", "8"}}},
                 {"medium", {{"ddgi.rays", "128"}, {"ddgi.fit_cells", "10"}}},
                 {"high", {{"ddgi.rays", "256"}, {"ddgi.fit_cells", "12"}}}};
    m.debugViews = ddgiDebugViews();
    m.stressCases = ddgiStressCases();
    m.benchVariants = {{"gl", {{"ddgi.backend", "gl"}}}, {"cpu", {{"ddgi.backend", "cpu"}}}};
    m.bench = runDdgiBench;
    return m;
}

}  // namespace voxgi
