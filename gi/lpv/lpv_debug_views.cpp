#include "gi/lpv/lpv_debug_views.h"

#include <algorithm>
#include <cmath>

#include "gi/sh/sh.h"
#include "shaders/shared/light_bricks.h"
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

const SettingsTable<LpvBricksOptions>& lpvBricksOptions() {
    static const SettingsTable<LpvBricksOptions> table = [] {
        SettingsTable<LpvBricksOptions> t(kLpvBricksView);
        t.integer("cascade", &LpvBricksOptions::cascade, 0, kLpvMaxCascades - 1, "the cascade shown");
        return t;
    }();
    return table;
}

std::vector<DebugViewInfo> lpvDebugViews() {
    return {cascadeBoundsView("the light volumes as placed for the current camera"),
            // Refreshed every 8 frames: each drawing reads the whole volume back from the GPU.
            {kLpvCellsView, "LPV cells", 'H',
             "one sphere per stride-th cell of a cascade that holds light, painted with the cell's 2-band SH toward "
             "each point's normal (ordinates: the irradiance a surface facing that way receives), the brightest "
             "cell's mean scaled to 1 before the exposure",
             lpvCellsOptions().info(), 8},
            {kLpvBricksView, "LPV bricks", 'K',
             "one box per 8^3 brick of a cascade that stores light (lpv.transport=ordinates: the bricks within a "
             "receiver's reach of the voxelized surfaces; none for sh)",
             lpvBricksOptions().info(), 8}};
}

DebugDrawing lpvBricks(const OrdinatesTransport& transport, int cascade, int cascades) {
    DebugDrawing d;
    const CascadeGrid& g = transport.grid();
    const glm::vec3 color = cascadeColor(cascade, cascades);
    for (const glm::ivec3& o : transport.bricks().slotOrigins()) {
        const glm::ivec3 end = glm::min(o + shading::kBrickSide, glm::ivec3(g.resolution));
        d.boxes.push_back({glm::vec3(g.origin + o) * g.cellSize, glm::vec3(g.origin + end) * g.cellSize, color});
    }
    return d;
}

DebugDrawing cascadeBounds(const std::vector<CascadePlacement>& cascades) {
    DebugDrawing d;
    for (std::size_t i = 0; i < cascades.size(); ++i)
        d.boxes.push_back({cascades[i].grid.worldMin(), cascades[i].grid.worldMax(),
                           cascadeColor(int(i), int(cascades.size()))});
    return d;
}

namespace {

// A sphere at every stride-th cell of the grid that holds light; cellSh(local, r, g, b) fills the
// cell's SH per colour. The SH scale maps the brightest cell's mean to 1, times 2^exposureStops.
template <class CellSh>
DebugDrawing cellSpheres(const CascadeGrid& g, int stride, float exposureStops, CellSh cellSh) {
    DebugDrawing d;
    d.shSpheres = true;
    auto onStride = [&](int v) { return ((v % stride) + stride) % stride == 0; };
    float brightest = 0.0f;
    for (int z = 0; z < g.resolution; ++z)
        for (int y = 0; y < g.resolution; ++y)
            for (int x = 0; x < g.resolution; ++x) {
                const glm::ivec3 local(x, y, z), cell = g.origin + local;
                if (!onStride(cell.x) || !onStride(cell.y) || !onStride(cell.z)) continue;
                glm::vec4 r(0.0f), gr(0.0f), b(0.0f);
                if (!cellSh(local, r, gr, b) || (r.x == 0.0f && gr.x == 0.0f && b.x == 0.0f)) continue;
                d.spheres.push_back({glm::vec4(g.cellCenter(local), 0.3f * g.cellSize * float(stride)), r, gr, b});
                brightest = std::max({brightest, r.x, gr.x, b.x});
            }
    // The mean over directions is c0 * Y00.
    d.shScale = brightest > 0.0f ? std::exp2(exposureStops) / (sh::kY00 * brightest) : 1.0f;
    return d;
}

}  // namespace

DebugDrawing lpvCellSpheres(const LightVolume& light, int stride, float exposureStops) {
    return cellSpheres(light.grid, stride, exposureStops, [&](glm::ivec3 local, glm::vec4& r, glm::vec4& g,
                                                              glm::vec4& b) {
        const std::size_t i = light.grid.index(local);
        if (i >= light.r.size()) return false;
        r = light.r[i], g = light.g[i], b = light.b[i];
        return true;
    });
}

DebugDrawing lpvCellSpheres(const OrdinatesTransport& transport, const IrradianceBricks& cube, int stride,
                            float exposureStops) {
    return cellSpheres(transport.grid(), stride, exposureStops, [&](glm::ivec3 local, glm::vec4& r, glm::vec4& g,
                                                                   glm::vec4& b) {
        if (transport.bricks().slotOf(local) < 0) return false;
        glm::vec3 e[kOrdinateFaces];
        for (int f = 0; f < kOrdinateFaces; ++f) e[f] = glm::vec3(transport.irradianceAt(cube, local, f));
        // E(n) ~ mean + n . half, in the basis (Y00, -Y1 n.y, Y1 n.z, -Y1 n.x) of gi/sh/sh.h.
        const glm::vec3 mean = (e[0] + e[1] + e[2] + e[3] + e[4] + e[5]) / 6.0f;
        const glm::vec3 hx = (e[0] - e[1]) * 0.5f, hy = (e[2] - e[3]) * 0.5f, hz = (e[4] - e[5]) * 0.5f;
        glm::vec4* out[3] = {&r, &g, &b};
        for (int k = 0; k < 3; ++k)
            *out[k] = glm::vec4(mean[k] / sh::kY00, -hy[k] / sh::kY1, hz[k] / sh::kY1, -hx[k] / sh::kY1);
        return true;
    });
}

}  // namespace voxgi
