#include "gi/lpv/lpv_desc.h"

#include "scenes/errors.h"

namespace voxgi {

namespace {
void requireRange(bool ok, const std::string& key, const std::string& range) {
    if (!ok) throw InputError("gi.lpv." + key + ": must be " + range);
}
}  // namespace

LpvDesc LpvDesc::fromSettings(const GiSettings& gi, bool cascaded) {
    gi.requireKnown("lpv", {"resolution", "cascades", "cell_size", "steps", "occlusion", "bounces", "rsm_size",
                            "gbuffer_blocker_size", "inject_normal_offset", "inject_light_offset",
                            "apply_normal_offset", "dampening", "glossy", "forward_offset", "fade_cells", "backend",
                            "sparse", "reuse", "static_blockers"});
    LpvDesc d;
    d.cascades = cascaded ? 3 : 1;
    d.resolution = gi.getInt("lpv.resolution", d.resolution);
    requireRange(d.resolution >= 4 && d.resolution <= 256 && d.resolution % 4 == 0, "resolution",
                 "a multiple of 4 in [4, 256]");
    d.cascades = gi.getInt("lpv.cascades", d.cascades);
    requireRange(d.cascades >= 1 && d.cascades <= 6, "cascades", "in [1, 6]");
    if (!cascaded && d.cascades != 1) throw InputError("gi.lpv.cascades: the lpv method has one volume; use clpv");
    d.cellSize = gi.getFloat("lpv.cell_size", d.cellSize);
    requireRange(d.cellSize >= 0.0f && d.cellSize < 1e30f, "cell_size", "positive (or 0 to fit the scene)");
    d.steps = gi.getInt("lpv.steps", d.steps);
    requireRange(d.steps >= 0 && d.steps <= 100000, "steps", "in [0, 100000]");
    d.occlusion = gi.getBool("lpv.occlusion", d.occlusion);
    d.bounces = gi.getBool("lpv.bounces", d.bounces);
    d.rsmSize = gi.getInt("lpv.rsm_size", d.rsmSize);
    requireRange(d.rsmSize >= 8 && d.rsmSize <= 4096, "rsm_size", "in [8, 4096]");
    d.gbufferBlockerSize = gi.getInt("lpv.gbuffer_blocker_size", d.gbufferBlockerSize);
    requireRange(d.gbufferBlockerSize >= 0 && d.gbufferBlockerSize <= 4096, "gbuffer_blocker_size", "in [0, 4096]");
    d.injectNormalOffset = gi.getFloat("lpv.inject_normal_offset", d.injectNormalOffset);
    d.injectLightOffset = gi.getFloat("lpv.inject_light_offset", d.injectLightOffset);
    d.applyNormalOffset = gi.getFloat("lpv.apply_normal_offset", d.applyNormalOffset);
    d.dampening = gi.getFloat("lpv.dampening", d.dampening);
    requireRange(d.dampening >= 0.0f, "dampening", "non-negative");
    d.glossy = gi.getBool("lpv.glossy", d.glossy);
    d.forwardOffset = gi.getFloat("lpv.forward_offset", d.forwardOffset);
    d.fadeCells = gi.getFloat("lpv.fade_cells", d.fadeCells);
    requireRange(d.fadeCells >= 0.0f && d.fadeCells * 2.0f < float(d.resolution), "fade_cells",
                 "non-negative and under half the resolution");
    d.backend = gi.getString("lpv.backend", d.backend);
    requireRange(d.backend == "cpu" || d.backend == "gl", "backend", "cpu or gl");
    d.sparse = gi.getBool("lpv.sparse", d.sparse);
    d.reuse = gi.getBool("lpv.reuse", d.reuse);
    d.staticBlockers = gi.getBool("lpv.static_blockers", d.staticBlockers);
    return d;
}

}  // namespace voxgi
