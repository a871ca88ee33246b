// The LPV's debug views: the cascades' bounds, one cascade's light volume as spheres painted
// with each cell's 2-band SH (what flows out of it, bright where light leaves) or, with the
// ordinates, with the irradiance a surface facing each point of the sphere would receive, and
// the ordinates' stored bricks.
#pragma once

#include <array>
#include <vector>

#include "gi/debug_view.h"
#include "gi/lpv/cascades.h"
#include "gi/lpv/ordinates.h"

namespace voxgi {

constexpr const char* kLpvCellsView = "lpv_cells";

struct LpvCellsOptions {
    int cascade = 0;
    int stride = 2;  // every n-th cell per axis
};
const SettingsTable<LpvCellsOptions>& lpvCellsOptions();

constexpr const char* kLpvBricksView = "lpv_bricks";

struct LpvBricksOptions {
    int cascade = 0;
};
const SettingsTable<LpvBricksOptions>& lpvBricksOptions();

// The views lpv and clpv declare.
std::vector<DebugViewInfo> lpvDebugViews();

DebugDrawing cascadeBounds(const std::vector<CascadePlacement>& cascades);
// One box per brick that cascade `cascade` of `cascades` stores (gi/lpv/brick_map.h; a brick
// past the grid's edge cut to it), in the cascade's colour.
DebugDrawing lpvBricks(const OrdinatesTransport& transport, int cascade, int cascades);
// A sphere at every `stride`-th cell (per axis, in world cell indices) holding light; the SH
// scale maps the brightest cell's mean intensity to 1, times 2^exposureStops.
DebugDrawing lpvCellSpheres(const LightVolume& light, int stride, float exposureStops);
// The same for `lpv.transport=ordinates`: the cell's six axis irradiances (px, nx, py, ny, pz,
// nz; rgb, W/m^2) as the 2-band SH of their mean plus the half-differences of opposite faces,
// so each sphere point shows what a surface facing that way receives; the brightest cell's mean
// maps to 1; cells of bricks not stored show nothing.
DebugDrawing lpvCellSpheres(const OrdinatesTransport& transport, const IrradianceBricks& cube, int stride,
                            float exposureStops);

}  // namespace voxgi
