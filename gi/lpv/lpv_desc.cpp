#include "gi/lpv/lpv_desc.h"

#include "scenes/errors.h"
#include "shaders/lpv/limits.h"

namespace voxgi {

namespace {

SettingsTable<LpvDesc> makeTable(bool cascaded) {
    using D = LpvDesc;
    SettingsTable<D> t("lpv");
    t.integer("resolution", &D::resolution, 8, 256, "cells per side of each cascade", 4).main();
    if (cascaded)
        t.integer("cascades", &D::cascades, 1, kLpvMaxCascades, "cascades, cell size doubling outward").main();
    else
        t.integer("cascades", &D::cascades, 1, 1, "lpv has one volume (clpv has cascades)");
    t.number("cell_size", &D::cellSize, 0.0, 1e6,
             cascaded ? "finest cell (m); 0 = fit: the coarsest cascade reaches the farthest scene corner from the camera"
                      : "cell (m); 0 = fit: the scene plus one cell of margin");
    t.integerOrFit("steps", &D::steps, 0, 100000,
                   "sh: most propagation iterations per cascade (cpu stops once converged); fit: the resolution, "
                   "so light crosses a cascade (ordinates: see sweeps)",
                   "fit")
        .main();
    t.flag("occlusion", &D::occlusion, "surfaces stop light (sh: attenuate by the blockers at the shared face)");
    t.flag("bounces", &D::bounces, "light reflected again off surfaces (sh: blockers) with their albedo");
    t.flag("static_blockers", &D::staticBlockers, "surfaces (sh: blockers) from the voxelized scene (cached .vdb), made once per cascade placement");
    t.flag("surfel_blockers", &D::surfelBlockers,
           "sh: blockers from each update's RSM and G-buffer surfels too; false: the voxelized ones alone, kept with the "
           "cascades");
    t.integer("rsm_size", &D::rsmSize, 8, 4096, "reflective shadow map size per light face");
    t.integer("sky_bounce_size", &D::skyBounceSize, 0, 4096,
              "sky bounce (0 = none); sh: surfaces the camera sees, lit by the sky volume, injected as VPLs from a grid "
              "this wide; ordinates: every voxelized surface");
    t.integer("gbuffer_blocker_size", &D::gbufferBlockerSize, 0, 4096,
              "sh: G-buffer blockers sampled on a grid this wide (0 = none)");
    t.number("inject_normal_offset", &D::injectNormalOffset, 0.0, 4.0, "VPL shift along the surfel normal, in cells");
    t.number("inject_light_offset", &D::injectLightOffset, 0.0, 4.0, "sh: VPL shift toward the light, in cells");
    t.number("apply_normal_offset", &D::applyNormalOffset, 0.0, 4.0, "lookup shift along the shading normal, in cells");
    t.choice("tap_visibility", &D::tapVisibility,
             {{"off", TapVisibility::Off},
              {"rays", TapVisibility::Rays},
              {"cells", TapVisibility::Cells},
              {"false", TapVisibility::Off},
              {"true", TapVisibility::Rays}},
             "ordinates: drop the trilinear taps in front of a receiver that a ray to their cell centre finds blocked; "
             "rays: per pixel (triangles' BVH on the GPU); cells: per cell and side, traced once per cascade placement "
             "(true = rays)");
    t.number("dampening", &D::dampening, 0.0, 100.0, "sh: gradient dampening strength (0 = off)");
    t.flag("glossy", &D::glossy, "glossy march of the finest cascade for specular or metallic materials with roughness < 0.6");
    t.number("forward_offset", &D::forwardOffset, 0.0, 0.5, "clpv: cascades centred this fraction of their size ahead of the camera");
    // At most 4 cells: a fade wider than half the smallest volume (8 cells) would never reach 1.
    t.number("fade_cells", &D::fadeCells, 0.0, 4.0, "clpv: width of each cascade's border fade, in cells");
    if (cascaded)
        t.choice("cascade_bounds", &D::cascadeBounds, {{"camera", CascadeBounds::Camera}, {"scene", CascadeBounds::Scene}},
                 "camera: the coarsest cascade reaches the scene's farthest corner from the camera, all centred ahead of "
                 "it; scene: the coarsest is the scene's bounds (no fade), finer ones follow the camera inside them");
    t.choice("backend", &D::backend, backendChoices(), "cpu (TBB reference) or gl (compute shaders)").main();
    t.flag("sparse", &D::sparse,
           "sh, cpu: propagate only the bricks holding light; ordinates: store the 8^3 bricks within a receiver's reach "
           "of the voxelized surfaces (false: every brick)");
    t.choice("transport", &D::transport, {{"sh", LpvTransport::Sh}, {"ordinates", LpvTransport::Ordinates}},
             "sh: seed 000's SH propagation; ordinates: direction bins swept across each cascade, every bounce");
    t.integer("ordinates_per_face", &D::ordinatesPerFace, 2, 8,
              "ordinates: direction bins per cube face along each lateral axis (6 x n^2 bins)", 2);
    t.integerOrFit("sweeps", &D::sweeps, 1, 256,
                   "ordinates: sweeps (bounces) per update; fit: until converged; a number continues from the last "
                   "update's reflections, converging over updates",
                   "fit");
    t.choice("cube_read", &D::cubeRead, {{"ambient", CubeRead::Ambient}, {"quadratic", CubeRead::Quadratic}},
             "ordinates: a receiver's irradiance from its cell's six axis faces: ambient, the faces its normal points "
             "along by n^2; quadratic, the quadratic in n through all six (closer for tilted normals)");
    t.flag("reuse", &D::reuse, "skip the update while lights, geometry and placement are unchanged");
    return t;
}

}  // namespace

const SettingsTable<LpvDesc>& lpvSettings(bool cascaded) {
    static const SettingsTable<LpvDesc> single = makeTable(false), cascades = makeTable(true);
    return cascaded ? cascades : single;
}

LpvDesc lpvDefaults(bool cascaded) {
    LpvDesc d;
    d.cascades = cascaded ? 3 : 1;
    if (cascaded) {
        // Measured on the Cornell box, Sibenik, Sponza and Sponza at noon (docs/lpv.md, "Reading
        // a cell's light"): 96 bins and the quadratic read lower clpv's relMSE and HDR-FLIP on both
        // layers of all four, at 2.3-3.7x the CPU solve. lpv keeps 24 bins and the n^2 read: on
        // Sponza its single volume gets worse with more bins (its arcade ceilings' excess).
        d.ordinatesPerFace = 4;
        d.cubeRead = CubeRead::Quadratic;
    }
    return d;
}

LpvDesc readLpvDesc(const GiSettings& gi, bool cascaded) {
    LpvDesc d = lpvSettings(cascaded).read(gi, lpvDefaults(cascaded));
    if (d.transport == LpvTransport::Ordinates && d.backend == Backend::Gl && d.sweeps != kFittedInteger)
        throw InputError("gi.lpv.sweeps: a number of sweeps (carried across updates) runs on the cpu back end only "
                         "(set lpv.backend=cpu or lpv.sweeps=fit)");
    return d;
}

int propagationSteps(const LpvDesc& desc) { return desc.steps == kFittedInteger ? desc.resolution : desc.steps; }

}  // namespace voxgi
