// The `lpv` and `clpv` methods as the tools see them: settings, plan, presets, views, stiff
// cases and benchmark variants.
#include <algorithm>
#include <cmath>
#include <string>

#include "gi/lpv/lpv_debug_views.h"
#include "gi/lpv/lpv_desc.h"
#include "gi/lpv/lpv_technique.h"
#include "gi/lpv/rsm.h"
#include "gi/method.h"
#include "gi/sky/sky_volume.h"

namespace voxgi {

namespace {

std::string count(std::size_t n, const std::string& what) {
    return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

TechniquePlan lpvPlan(const Scene& scene, bool cascaded) {
    const LpvDesc d = readLpvDesc(scene.gi, cascaded);
    TechniquePlan p;
    // The sky bounce needs the frame's sky volume (render/frame/frame_plan.cpp: a sky, triangles
    // and sky.light).
    std::string noSkyBounce;
    if (!scene.sky.enabled) noSkyBounce = "no sky";
    else if (scene.triangleCount() == 0) noSkyBounce = "no triangles";
    else if (!readSkyVolumeDesc(scene.gi).light) noSkyBounce = "sky.light=false";
    else if (d.skyBounceSize <= 0) noSkyBounce = "lpv.sky_bounce_size=0";
    if (scene.lights.empty() && !noSkyBounce.empty()) {
        for (const char* pass : {"lpv.rsm", "lpv.sky_bounce", "lpv.inject", "lpv.blockers", "lpv.propagate", "lpv.apply"})
            p.skipped.push_back({pass, "no lights and no sky bounce (" + noSkyBounce + "): nothing to inject"});
        return p;
    }
    const bool gl = d.backend == Backend::Gl;
    const bool voxels = d.staticBlockers && scene.triangleCount() > 0;
    const std::string volumes = count(std::size_t(d.cascades), "cascade") + " of " + std::to_string(d.resolution) + "^3";
    p.updateIf(voxels, "lpv.static_blockers",
               d.transport == LpvTransport::Ordinates
                   ? std::string("the voxelized scene's surfaces (area, normal, albedo) per cell, made when a cascade "
                                 "moves, kept while it stays")
                   : std::string("voxelized-scene blockers made") + (gl ? " and uploaded" : "") +
                         " when a cascade moves, kept while it stays",
               d.staticBlockers ? "no triangles" : "lpv.static_blockers=false");
    p.updateIf(!scene.lights.empty(), "lpv.rsm",
               count(rsmFaceCount(scene), "reflective shadow map face") + " of " + std::to_string(d.rsmSize) + "^2 for " +
                   count(scene.lights.size(), "light"),
               "no lights");
    p.updateIf(noSkyBounce.empty(), "lpv.sky_bounce",
               d.transport == LpvTransport::Ordinates
                   ? std::string("every voxelized surface lit by the sky volume reflects into the bins")
                   : "the G-buffer on a " + std::to_string(d.skyBounceSize) +
                         "^2 grid, lit by the sky volume, as VPLs (surfaces on screen only)",
               noSkyBounce);
    const bool ordinates = d.transport == LpvTransport::Ordinates;
    const bool surfelBlockers = d.surfelBlockers && !ordinates;
    if (!gl)
        p.updateIf(surfelBlockers && d.gbufferBlockerSize > 0, "lpv.gbuffer_readback",
                   "camera blockers: the G-buffer read back on a " + std::to_string(d.gbufferBlockerSize) + " grid",
                   ordinates ? "lpv.transport=ordinates: surfaces from the voxelized scene only"
                   : !d.surfelBlockers ? "lpv.surfel_blockers=false"
                                       : "lpv.gbuffer_blocker_size=0");
    const std::string sourcesName = scene.lights.empty() ? "sky-bounce" : "RSM";
    if (ordinates) {
        const int bins = 6 * d.ordinatesPerFace * d.ordinatesPerFace;
        p.update.push_back({"lpv.inject", sourcesName + " surfels' power into " + std::to_string(bins) +
                                              " direction bins of " + volumes});
        p.skipped.push_back({"lpv.blockers", "lpv.transport=ordinates: the voxelized surfaces stop the light"});
        p.update.push_back({"lpv.propagate", std::to_string(bins) + " bins swept across " + volumes +
                                                 (d.bounces ? ", one sweep per bounce until under 1e-3 of the light is left"
                                                            : ", one sweep (lpv.bounces=false)") +
                                                 (gl ? " on gl, into the irradiance cubes' brick pool"
                                                     : " on cpu, irradiance cubes uploaded to the brick pool")});
    } else {
        p.update.push_back({"lpv.inject", sourcesName + " surfels as virtual point lights into " + volumes});
        std::vector<std::string> sources;
        if (surfelBlockers) sources.push_back("the RSMs");
        if (surfelBlockers && d.gbufferBlockerSize > 0) sources.push_back("the G-buffer");
        if (voxels) sources.push_back("the voxelized scene");
        std::string from;
        for (std::size_t i = 0; i < sources.size(); ++i) from += (i == 0 ? "" : ", ") + sources[i];
        p.updateIf(!sources.empty(), "lpv.blockers",
                   "blockers from " + from + (surfelBlockers ? "" : " (kept while the cascades stay)"),
                   "no blocker source: lpv.static_blockers=false and lpv.surfel_blockers=false");
        p.update.push_back({"lpv.propagate", std::to_string(propagationSteps(d)) + " steps in " + volumes + " on " +
                                                 (gl ? "gl" : d.sparse ? "cpu (sparse)" : "cpu (dense)")});
        if (!gl) p.update.push_back({"lpv.upload", "light volumes to 3D textures"});
    }
    p.apply.push_back({"lpv.apply", std::string(ordinates ? "irradiance from the cubes" : "irradiance from the light volumes") +
                                        (d.glossy && scene.hasGlossyOrRefractive() ? " and the glossy march" : "")});
    if (d.reuse) p.notes.push_back("lpv update passes run again only when the lights, geometry or cascade placement change");
    return p;
}

std::vector<StressCase> lpvStressCases() {
    std::vector<StressCase> cases;
    for (const char* albedo : {"0.99", "0.999"}) {
        StressCase c;
        c.name = std::string("box-albedo-") + albedo;
        c.description = std::string("closed box, albedo ") + albedo + ", point light, SH transport, 64 steps with bounces";
        c.scene = StressCase::SceneKind::ClosedBox;
        c.albedo = std::stof(albedo);
        c.settings = [](const Scene&) {
            return SettingList{{"lpv.resolution", "16"}, {"lpv.transport", "sh"}, {"lpv.steps", "64"}};
        };
        cases.push_back(c);
        // The ordinates sweep until the light left is 1e-3 of the emitted or 256 bounces: at
        // albedo 0.999 the cap ends it, with every bounce's light still finite and positive.
        StressCase o = c;
        o.name = std::string("ordinates-box-albedo-") + albedo;
        o.description = std::string("closed box, albedo ") + albedo + ", point light, ordinates swept to convergence";
        o.settings = [](const Scene&) { return SettingList{{"lpv.resolution", "16"}, {"lpv.transport", "ordinates"}}; };
        cases.push_back(o);
    }
    StressCase steps;
    steps.name = "10000-steps";
    steps.description = "closed box albedo 0.9, 8^3 cells, 10,000 CPU SH propagation steps against 2,000";
    steps.scene = StressCase::SceneKind::ClosedBox;
    steps.size = 16;
    steps.settings = [](const Scene&) {
        return SettingList{{"lpv.resolution", "8"}, {"lpv.backend", "cpu"}, {"lpv.transport", "sh"}, {"lpv.steps", "10000"}};
    };
    steps.against = [](const Scene&) {
        return SettingList{{"lpv.resolution", "8"}, {"lpv.backend", "cpu"}, {"lpv.transport", "sh"}, {"lpv.steps", "2000"}};
    };
    steps.tolerance = 1e-3;
    cases.push_back(steps);
    return cases;
}

MethodInfo lpvFamily(bool cascaded) {
    MethodInfo m;
    m.name = cascaded ? "clpv" : "lpv";
    m.summary = cascaded ? "cascaded light propagation volumes centred on the camera (seed 000)"
                         : "one light propagation volume fitted to the scene (seed 000)";
    declareSettings(m, lpvSettings(cascaded), lpvDefaults(cascaded));
    m.memoryBytes = [cascaded](const GiSettings& gi) {
        // Measured peak resident memory (CPU propagation, its sparse index and the GL textures,
        // on llvmpipe all in host memory): 370-650 bytes per cell at 64^3-128^3, 1-2 cascades.
        // The reflective shadow maps: a batch of faces' render targets (68 bytes per texel, at
        // most 256 MiB unless one face is larger: RsmRenderer::facesPerBatch), and in the cpu
        // back end one face read back and its surfels (64 + 64 bytes per texel) at a time.
        // Measured on the Cornell box's 5 faces: 319, 194 and 195 bytes per face texel at
        // 1024^2 (3 faces a batch), 2048^2 and 4096^2 (one). Cascades after the first also hold
        // their inner light (gi/lpv/cascades.h): injected, accumulated and their textures (cpu) or
        // injected, ping, pong and accumulated (gl), 4 x 48 bytes per cell. The gl back end's
        // face blockers and albedo (gi/lpv/gl_propagation.cpp): 2 x 3 x 16 bytes per corner.
        const LpvDesc d = readLpvDesc(gi, cascaded);
        const double texels = double(d.rsmSize) * double(d.rsmSize);
        const double cells = double(d.resolution) * double(d.resolution) * double(d.resolution);
        const double rsm = std::max(256.0 * 1024.0 * 1024.0, 68.0 * texels) + 132.0 * texels;
        if (d.transport == LpvTransport::Ordinates) {
            // Per cell of each cascade's stored bricks: the ring and inner irradiance cubes in the
            // GL brick pool (2 x 96 bytes), one cube per group of bins while solving (4 x 96), the
            // returned cube (96) and the surface index (4). Per surface cell: the ring and inner
            // sources and the sweeps' copy (3 x 12 bytes per bin) and its area, normal, albedo and
            // reflections (5 x 72 + 40); surface cells were 18 % of the cells on the Cornell box
            // and Sponza at 32^3, a quarter is assumed. Before the scene is voxelized the bricks
            // are not known: every brick is assumed stored (lpv.sparse=false's worst case; Sponza
            // stores 50-100 %, docs/lpv.md "Sparse light volumes").
            const double bins = 6.0 * double(d.ordinatesPerFace) * double(d.ordinatesPerFace);
            const double bricked = std::pow(std::ceil(double(d.resolution) / 8.0) * 8.0, 3.0);
            double perCascade = bricked * 676.0 + cells * 0.25 * (36.0 * bins + 400.0);
            if (d.backend == Backend::Gl) {
                // The GPU's buffers (gi/lpv/gl_ordinates.cpp): irradiance by axis group (288 bytes a
                // stored cell, allocated as requested); at twice the request, reflections (288 a
                // surface cell), sources and plane shares (16 a bin and surface cell), two padded
                // slabs of every bin's four taps (64 bytes a lateral cell and bin).
                const double side = double(d.resolution + 2);
                perCascade += bricked * 288.0 +
                              2.0 * (0.25 * cells * (288.0 + 16.0 * bins) + 2.0 * bins * side * side * 64.0);
            }
            return double(d.cascades) * perCascade + rsm;
        }
        const double corners = double(d.resolution + 1) * double(d.resolution + 1) * double(d.resolution + 1);
        return 500.0 * cells * double(d.cascades) + 192.0 * cells * double(d.cascades - 1) +
               96.0 * corners * double(d.cascades) + rsm;
    };
    m.create = [cascaded](const Scene& s) { return createLpvTechnique(s, readLpvDesc(s.gi, cascaded), cascaded); };
    m.plan = [cascaded](const Scene& s) { return lpvPlan(s, cascaded); };
    // lpv.reuse=false: an unchanged frame would skip its work and eval would time an empty frame.
    const SettingList timed{{"lpv.reuse", "false"}};
    auto preset = [&](const char* name, const char* resolution, const char* steps, const char* cascades) {
        Preset p{name, {{"lpv.resolution", resolution}, {"lpv.steps", steps}}};
        if (cascaded) p.settings.push_back({"lpv.cascades", cascades});
        p.settings.insert(p.settings.end(), timed.begin(), timed.end());
        return p;
    };
    // Steps fitted to the resolution (light crosses each cascade once) in every preset; lpv's
    // high preset has finer cells (with fitted steps, 32^3 and 32 steps would equal medium),
    // clpv's one more cascade.
    m.presets = {preset("low", "16", "fit", "2"), preset("medium", "32", "fit", "3"),
                 preset("high", cascaded ? "32" : "48", "fit", "4")};
    m.debugViews = lpvDebugViews();
    if (!cascaded) m.stressCases = lpvStressCases();
    // cpu-sparse, cpu-dense and gl-sh name seed 000's SH transport (their names predate the
    // ordinates becoming the default and keep their meaning in the docs' commands).
    const SettingList sh{{"lpv.transport", "sh"}, {"lpv.reuse", "false"}},
        ordinates{{"lpv.transport", "ordinates"}, {"lpv.reuse", "false"}};
    auto variant = [](const char* name, SettingList settings, const SettingList& more) {
        settings.insert(settings.end(), more.begin(), more.end());
        return Preset{name, settings};
    };
    m.benchVariants = {variant("cpu-sparse", {{"lpv.backend", "cpu"}, {"lpv.sparse", "true"}}, sh),
                       variant("cpu-dense", {{"lpv.backend", "cpu"}, {"lpv.sparse", "false"}}, sh),
                       variant("gl-sh", {{"lpv.backend", "gl"}}, sh),
                       variant("gl", {{"lpv.backend", "gl"}}, ordinates),
                       variant("cpu-ordinates", {{"lpv.backend", "cpu"}}, ordinates)};
    return m;
}

}  // namespace

MethodInfo lpvMethod() { return lpvFamily(false); }
MethodInfo clpvMethod() { return lpvFamily(true); }

}  // namespace voxgi
