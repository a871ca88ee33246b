#include "gi/lpv/lpv_debug_views.h"

#include <algorithm>
#include <cmath>

#include "gi/sh/sh.h"
#include "shaders/lpv/limits.h"

namespace voxgi {

const SettingsTable<LpvCellsOptions>& lpvCellsOptions() {
    static const SettingsTable<LpvCellsOptions> table = [] {
        SettingsTable<LpvCellsOptions> t(kLpvCellsView);
        t.integer("cascade", &LpvCellsOptions::cascade, 0, kLpvMaxCascades - 1, "the cascade shown");
        t.integer("stride", &LpvCellsOptions::stride, 1, 8, "every n-th cell per axis");
        return t;
    }();
    return table;
}

std::vector<DebugViewInfo> lpvDebugViews() {
    return {cascadeBoundsView("the light volumes as placed for the current camera"),
            // Refreshed every 8 frames: each drawing reads the whole volume back from the GPU.
            {kLpvCellsView, "LPV cells", 'H',
             "one sphere per stride-th cell of a cascade that holds light, painted with the cell's 2-band SH toward "
             "each point's normal, the brightest cell's mean scaled to 1 before the exposure",
             lpvCellsOptions().info(), 8}};
}

DebugDrawing cascadeBounds(const std::vector<CascadePlacement>& cascades) {
    DebugDrawing d;
    for (std::size_t i = 0; i < cascades.size(); ++i)
        d.boxes.push_back({cascades[i].grid.worldMin(), cascades[i].grid.worldMax(),
                           cascadeColor(int(i), int(cascades.size()))});
    return d;
}

DebugDrawing lpvCellSpheres(const LightVolume& light, int stride, float exposureStops) {
    DebugDrawing d;
    d.shSpheres = true;
    const CascadeGrid& g = light.grid;
    auto onStride = [&](int v) { return ((v % stride) + stride) % stride == 0; };
    float brightest = 0.0f;
    for (int z = 0; z < g.resolution; ++z)
        for (int y = 0; y < g.resolution; ++y)
            for (int x = 0; x < g.resolution; ++x) {
                const glm::ivec3 local(x, y, z), cell = g.origin + local;
                if (!onStride(cell.x) || !onStride(cell.y) || !onStride(cell.z)) continue;
                const std::size_t i = g.index(local);
                if (i >= light.r.size() || (light.r[i].x == 0.0f && light.g[i].x == 0.0f && light.b[i].x == 0.0f))
                    continue;
                d.spheres.push_back({glm::vec4(g.cellCenter(local), 0.3f * g.cellSize * float(stride)), light.r[i],
                                     light.g[i], light.b[i]});
                brightest = std::max({brightest, light.r[i].x, light.g[i].x, light.b[i].x});
            }
    // The mean intensity over directions is c0 * Y00.
    d.shScale = brightest > 0.0f ? std::exp2(exposureStops) / (sh::kY00 * brightest) : 1.0f;
    return d;
}

}  // namespace voxgi
