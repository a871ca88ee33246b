// DDGI as a GiTechnique ("ddgi"): update() traces, shades and blends the probe field; the
// apply pass adds (1-m)(1-s) albedo/pi * E_indirect; dumpVdb writes the probes as OpenVDB grids.
#pragma once

#include <memory>

#include "gi/ddgi/ddgi_system.h"
#include "gi/technique.h"

namespace voxgi {

struct NanoGeometry;

class DdgiGpu;

class DdgiTechnique : public GiTechnique {
public:
    // Needs a current GL context. Reads the `ddgi.*` settings of scene.gi.
    explicit DdgiTechnique(const Scene& scene, GeometryQuery query = {});
    ~DdgiTechnique() override;

    std::string name() const override { return "ddgi"; }
    void update(const FrameInput& input, const GBufferView& gbuffer) override;
    void applyIndirect(const FrameInput& input, const GBufferView& gbuffer) override;
    void dumpVdb(const std::string& path) const override;
    DebugDrawing debugView(const std::string& view, const DebugViewContext& context) const override;
    std::vector<TechniqueStat> stats() const override { return statList(lastStats_); }
    void trackConvergence() override { system_->trackChange(); }
    std::optional<double> lightStateChange() const override { return system_->fieldChange(); }

    DdgiSystem& system() { return *system_; }
    const DdgiFrameStats& lastStats() const { return lastStats_; }

private:
    std::unique_ptr<RayTracer> tracer_;
    std::unique_ptr<DdgiSystem> system_;
    std::unique_ptr<DdgiGpu> gpu_;
    DdgiFrameStats lastStats_;
};

// Writes probe_position, probe_offset, probe_state and probe_irradiance (mean per probe) grids,
// one set per cascade (suffix _c1, _c2... after the first), index space = logical probe grid;
// with `traceVolume` (ddgi.trace = volume) also its grids, trace_normal, trace_albedo and
// trace_surface_offset.
void writeProbeVdb(const ProbeField& field, const std::string& path, const NanoGeometry* traceVolume = nullptr);

}  // namespace voxgi
