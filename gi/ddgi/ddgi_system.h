// One DDGI field updated frame by frame on the CPU side: scroll, trace, shade, blend (through a
// BlendBackend: the CPU reference or GL compute), border, relocate and classify. No GL needed
// with the CPU backend, so tests and benchmarks can drive it directly.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gi/ddgi/ddgi_desc.h"
#include "gi/ddgi/hit_cache.h"
#include "gi/ddgi/hit_shading.h"
#include "gi/ddgi/probe_blend.h"
#include "gi/ddgi/probe_field.h"
#include "gi/ddgi/probe_rays.h"
#include "gi/ddgi/probe_states.h"
#include "gi/technique_stat.h"

namespace voxgi {

class RayTracer;

struct DdgiFrameStats {
    double traceMs = 0, shadeMs = 0, blendMs = 0, borderMs = 0, classifyMs = 0;
    // Parts of shadeMs: merging the hit-cache tables, evaluating the groups, shading each hit.
    double shadeMergeMs = 0, shadeGroupsMs = 0, shadeHitsMs = 0;
    std::int64_t raysTraced = 0;      // probe rays (fixed + blend)
    std::int64_t shadowQueries = 0;   // shadow rays (at hits, or into the occlusion probes)
    std::int64_t cacheGroups = 0;     // hit-cache groups (probe gathers shared by nearby hits)
    std::int64_t cacheGroupsEvaluated = 0;  // of those, evaluated this frame (hit_cache_refresh)
    std::int64_t cachedHits = 0;
    int probesBlended = 0;
    ProbeStateCounts states;
    // The update (frame number) raysTraced, probesBlended and states describe: this one on the
    // CPU; a GPU update's come back a frame or more later (DdgiGpu::updateProbes), -1 until then.
    std::int64_t countedFrame = -1;
};

// Every number of a frame's stats by name (times in ms), for the technique's stats() and the
// benchmark's medians.
std::vector<TechniqueStat> statList(const DdgiFrameStats& stats);

class DdgiSystem {
public:
    // Borrows `tracer` (and its scene), which must outlive the system.
    DdgiSystem(const RayTracer& tracer, const DdgiDesc& desc, GeometryQuery query = {});
    ~DdgiSystem();

    // One frame. Scrolling volumes centre ahead of `eye` along the unit `forward`
    // (scrollCentre). The CPU reference blends when backend is null.
    DdgiFrameStats update(glm::vec3 eye, BlendBackend* backend = nullptr, glm::vec3 forward = glm::vec3(0.0f));

    // Where the probes find the sky from the next update on (hit_shading.h); by default misses
    // see it.
    void setSky(const ProbeSky& sky) { sky_ = sky; }

    ProbeField& field() { return *field_; }
    const ProbeField& field() const { return *field_; }
    const DdgiDesc& desc() const { return field_->desc(); }
    const RayTracer& tracer() const { return tracer_; }
    std::uint32_t frame() const { return frame_; }
    // The rays and surfels of the last update (for benchmarks and tests).
    const RaySet& lastRays() const { return rays_; }
    const ProbeTrace& lastTrace() const { return trace_; }

    // How much the field still moves: |total now - total kChangeWindow updates ago| over the
    // total now, the total being every probe's mean irradiance summed (colours summed); negative
    // until kChangeWindow updates ran after trackChange() (off by default: it reads every probe's
    // irradiance each update). The window is the default sleep interval, so a sleeping probe
    // counts its updates too. The total, not each probe's change: a settled probe keeps the
    // rotated rays' noise (hysteresis 0.97 leaves about 12 % of one update's), which a sum over
    // probes of |change| measures forever (2-3 % on Sponza at noon, whose bounce-only probes see a
    // few bright hits among dark ones) while the sum averages it out (0.1 %); a field that is
    // still filling up rises everywhere and moves the total.
    static constexpr int kChangeWindow = 10;
    double fieldChange() const { return fieldChange_; }
    void trackChange() { trackChange_ = true; }

private:
    // The rest of update() when the backend runs the whole update (updatesProbes()).
    void updateElsewhere(DdgiFrameStats& stats, BlendBackend& backend);
    void blendAndClassify(DdgiFrameStats& stats, BlendBackend& blender, const std::vector<int>& blendProbes,
                          const std::vector<BlendJob>& jobs);
    void measureChange();

    const RayTracer& tracer_;
    GeometryQuery query_;
    std::unique_ptr<ProbeField> field_;
    std::unique_ptr<LightVisibility> shadowRays_;
    Bounds bounds_;  // the scene's, where scrolling volumes stay (scrollCentre)
    HitCache hitCache_;
    CpuBlend cpuBlend_;
    RaySet rays_;
    ProbeTrace trace_;
    ShadedRays shaded_;
    ShadeWorkspace shadeWorkspace_;
    ProbeSky sky_;
    std::uint32_t frame_ = 0;
    std::deque<std::vector<glm::vec3>> meanHistory_;  // per-probe mean irradiance, oldest first
    double fieldChange_ = -1.0;
    bool trackChange_ = false;
};

}  // namespace voxgi
