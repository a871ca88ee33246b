// Settings of the light propagation volume methods (`lpv`: one volume fitted to the scene;
// `clpv`: camera-centred cascades), the `gi.lpv.*` keys. Defaults are the members' initial
// values; ranges and docs are in the table (lpv_desc.cpp), printed by `voxgi methods lpv`.
#pragma once

#include "gi/backend.h"
#include "gi/settings_table.h"

namespace voxgi {

// How light moves between cells: seed 000's 2-band SH propagation, or direction bins swept
// across the volume (gi/lpv/ordinates.h), which keep a surface's light from returning to it.
enum class LpvTransport { Sh, Ordinates };

// Where clpv's cascades reach (gi/lpv/cascades.h): Camera, the coarsest from the camera to the
// scene's farthest corner, every cascade centred ahead of the camera; Scene, the coarsest the
// scene's bounds plus a cell (no border fade: nothing lies outside), finer ones following the
// camera but kept inside the bounds, so no cell lies where nothing can send or receive light.
enum class CascadeBounds { Camera, Scene };

// How a receiver reads a cell's irradiance cube (ordinates; shaders/shared/irradiance_cube.h):
// Ambient, the three faces its normal points along by n^2; Quadratic, the quadratic in the normal
// that takes the six faces' values on the axis normals (closer for tilted normals, docs/lpv.md).
enum class CubeRead { Ambient, Quadratic };

// Which trilinear taps a receiver reads (ordinates). Off: all eight. Rays: each tap whose cell
// centre lies in front of the receiver's surface is kept when a ray from the surface to the
// centre meets no triangle (the scene's BVH on the GPU, per pixel); taps behind the surface are
// kept. Cells: the same test made once per cascade placement from points on the surfaces of the
// receiver's cell that face its side (gi/lpv/tap_masks.h).
enum class TapVisibility { Off, Rays, Cells };

struct LpvDesc {
    int resolution = 32;        // cells per side of every cascade (32^3, as CryEngine and seed 000)
    int cascades = 1;           // 1 for lpv, 3 for clpv
    float cellSize = 0.0f;      // finest cell edge in metres; 0 = fit
    // Propagation iterations per cascade; fit (kFittedInteger): the resolution, so light crosses
    // a cascade once. Seed 000 used 12-16 at 32^3, which carries light half way: the Cornell
    // box's walls got 0.55-0.79 of the reference's indirect at 16 steps, 0.67-0.92 at 32.
    int steps = kFittedInteger;
    bool occlusion = true;      // attenuate by (1 - blocker) at the shared face
    bool bounces = true;        // extra bounces off blockers with their albedo (seed 000 eq. 3.7)
    int rsmSize = 256;          // reflective shadow map resolution per light (face)
    int gbufferBlockerSize = 128;  // G-buffer blockers injected after downsampling to this
    // The sky's bounce (gi/lpv/sky_bounce.h): the G-buffer sampled on a grid this wide, every
    // sample a VPL of the sky light it reflects; 0 = none. Runs only with the sky volume.
    int skyBounceSize = 256;
    float injectNormalOffset = 0.5f;  // VPL shift along the surfel normal, in cells
    float injectLightOffset = 0.25f;  // VPL shift toward the light, in cells
    float applyNormalOffset = 0.5f;   // lookup shift along the shading normal, in cells
    float dampening = 0.0f;     // gradient dampening strength (0 = off)
    bool glossy = true;         // glossy reflections by marching the finest cascade
    float forwardOffset = 0.25f;  // clpv: cascades centred this fraction of their size ahead
    float fadeCells = 2.0f;     // clpv: width of the border fade, in cells
    CascadeBounds cascadeBounds = CascadeBounds::Scene;  // clpv: see CascadeBounds
    Backend backend = Backend::Cpu;
    bool sparse = true;         // sh, cpu: propagate only bricks holding light; ordinates: bricks near surfaces only
    bool reuse = true;          // skip the update while lights, geometry and placement are unchanged
    bool staticBlockers = true; // blockers from the voxelized scene, made once per cascade placement
    // Blockers from each update's RSM and G-buffer surfels, merged with the static ones (seed
    // 000's only source). Off: the voxelized blockers alone, which stay the same while the
    // cascades stay, so the CPU operator and the GL geometry volumes persist across updates
    // (the surfels' blockers follow the G-buffer's jitter and every light move). See docs/lpv.md,
    // "Surfel blockers", for what each choice does to the light.
    bool surfelBlockers = true;
    LpvTransport transport = LpvTransport::Ordinates;
    // ordinates: bins per cube face along each lateral axis (6 x n^2 bins: 24 at 2, 96 at 4);
    // clpv's default is 4 (lpvDefaults).
    int ordinatesPerFace = 2;
    // ordinates: sweeps (bounces) per update; fit: until converged. A number carries the last
    // sweep's reflections into the next update, which converges over updates (one bounce of lag
    // per sweep) at that many sweeps' cost each.
    int sweeps = kFittedInteger;
    CubeRead cubeRead = CubeRead::Ambient;  // ordinates: see CubeRead; clpv's default is Quadratic (lpvDefaults)
    // ordinates: a receiver reads only the cells it sees (TapVisibility).
    TapVisibility tapVisibility = TapVisibility::Off;
};

// The table of `lpv` (cascaded = false: one volume) or `clpv`.
const SettingsTable<LpvDesc>& lpvSettings(bool cascaded);
// The defaults of each method (clpv: three cascades).
LpvDesc lpvDefaults(bool cascaded);
// Reads `lpv.*` over the defaults; InputError names the key of an unknown or refused value.
LpvDesc readLpvDesc(const GiSettings& gi, bool cascaded);
// The steps to run: desc.steps, or the resolution when fitted.
int propagationSteps(const LpvDesc& desc);

}  // namespace voxgi
