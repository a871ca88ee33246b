// Settings of the light propagation volume methods (`lpv`: one volume fitted to the scene;
// `clpv`: camera-centred cascades), read from the scene's `gi.lpv` block or `--set lpv.KEY=V`.
#pragma once

#include <string>

#include "scenes/gi_settings.h"

namespace voxgi {

struct LpvDesc {
    int resolution = 32;        // cells per side of every cascade (32^3, as CryEngine and seed 000)
    int cascades = 1;           // 1 for lpv, 3 for clpv
    float cellSize = 0.0f;      // finest cell edge in metres; 0 = fit: lpv covers the scene,
                                // clpv makes the coarsest cascade cover the scene
    int steps = 16;             // propagation iterations per cascade (seed 000: 12-16)
    bool occlusion = true;      // attenuate by (1 - blocker) at the shared face
    bool bounces = true;        // extra bounces off blockers with their albedo (seed 000 eq. 3.7)
    int rsmSize = 256;          // reflective shadow map resolution per light (face)
    int gbufferBlockerSize = 128;  // G-buffer blockers injected after downsampling to this
    float injectNormalOffset = 0.5f;  // VPL shift along the surfel normal, in cells
    float injectLightOffset = 0.25f;  // VPL shift toward the light, in cells
    float applyNormalOffset = 0.5f;   // lookup shift along the shading normal, in cells
    float dampening = 0.0f;     // gradient dampening strength (0 = off)
    bool glossy = true;         // glossy reflections by marching the finest cascade
    float forwardOffset = 0.25f;  // clpv: cascades centred this fraction of their size ahead
    float fadeCells = 2.0f;     // clpv: width of the border fade, in cells
    std::string backend = "cpu";  // cpu (TBB reference) or gl (compute shaders)
    bool sparse = true;         // cpu: propagate only bricks holding light (dilated per step)
    bool reuse = true;          // skip the update while lights, geometry and placement are unchanged
    bool staticBlockers = true; // blockers from the voxelized scene (volumes/, cached .vdb) merged
                                // with the dynamic RSM and G-buffer blockers

    // Reads `lpv.*`; unknown keys and out-of-range values raise InputError.
    static LpvDesc fromSettings(const GiSettings& gi, bool cascaded);
};

}  // namespace voxgi
