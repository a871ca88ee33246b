#include "gi/ddgi/ddgi_system.h"

#include <chrono>
#include <cmath>

#include "gi/ddgi/occlusion_probes.h"
#include "gi/ddgi/probe_sampling.h"
#include "gi/raytrace/ray_tracer.h"

namespace voxgi {

namespace {
double msSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}
}  // namespace

DdgiSystem::DdgiSystem(const RayTracer& tracer, const DdgiDesc& desc, GeometryQuery query)
    : tracer_(tracer), query_(std::move(query)) {
    const Scene& scene = tracer.scene();
    const glm::vec3 view = scene.camera.target - scene.camera.eye;
    const glm::vec3 forward = glm::length(view) > 0.0f ? glm::normalize(view) : glm::vec3(0.0f);
    bounds_ = scene.bounds();
    field_ = std::make_unique<ProbeField>(desc, layoutVolumes(desc, bounds_, scene.camera.eye, forward));
    shadowRays_ = std::make_unique<ShadowRayVisibility>(tracer, surfaceRayOffset(scene));
}

DdgiSystem::~DdgiSystem() = default;

std::vector<TechniqueStat> statList(const DdgiFrameStats& s) {
    return {{"trace", s.traceMs, "ms"},
            {"shade", s.shadeMs, "ms"},
            {"shade_merge", s.shadeMergeMs, "ms"},
            {"shade_groups", s.shadeGroupsMs, "ms"},
            {"shade_hits", s.shadeHitsMs, "ms"},
            {"blend", s.blendMs, "ms"},
            {"border", s.borderMs, "ms"},
            {"classify", s.classifyMs, "ms"},
            {"rays_traced", double(s.raysTraced), "rays"},
            {"shadow_queries", double(s.shadowQueries), "queries"},
            {"cache_groups", double(s.cacheGroups), "groups"},
            {"cache_groups_evaluated", double(s.cacheGroupsEvaluated), "groups"},
            {"cached_hits", double(s.cachedHits), "hits"},
            {"probes_blended", double(s.probesBlended), "probes"},
            {"probes_active", double(s.states.active), "probes"},
            {"probes_sleeping", double(s.states.sleeping), "probes"},
            {"probes_off", double(s.states.off), "probes"}};
}

DdgiFrameStats DdgiSystem::update(glm::vec3 eye, BlendBackend* backend, glm::vec3 forward) {
    DdgiFrameStats stats;
    ProbeField& field = *field_;
    const DdgiDesc& desc = field.desc();
    if (desc.scrolls())
        for (int v = 0; v < int(field.volumes().size()); ++v) {
            const glm::vec3 centre = scrollCentre(field.volumes()[std::size_t(v)], eye, forward, desc.forwardOffset, bounds_);
            // Scrolling resets probes in the CPU atlases, which must hold the newest field first.
            if (backend && field.scrollShift(v, centre) != glm::ivec3(0)) backend->syncToCpu(field);
            field.scrollTo(v, centre);
        }

    auto t0 = std::chrono::steady_clock::now();
    rays_ = makeRaySet(desc, std::uint32_t(desc.seed), frame_);
    if (backend && backend->updatesProbes()) {
        updateElsewhere(stats, *backend);
        return stats;
    }
    trace_.work = scheduleProbes(field, frame_, bool(query_.distanceToGeometry));
    std::vector<int> blendProbes;
    for (int p = 0; p < field.probeCount(); ++p)
        if (trace_.work[std::size_t(p)] == ProbeWork::Full) blendProbes.push_back(p);
    stats.probesBlended = int(blendProbes.size());

    // Hits are grouped for the hit cache while they are traced.
    const bool grouping = hitCacheUsed(desc, tracer_.scene());
    if (grouping) hitCache_.begin(hitCacheCellSize(field), std::size_t(field.probeCount()) * std::size_t(rays_.blendRays));
    traceProbes(tracer_, field, rays_, trace_, grouping ? &hitCache_ : nullptr);
    stats.traceMs = msSince(t0);
    stats.raysTraced = trace_.raysTraced;

    t0 = std::chrono::steady_clock::now();
    if (grouping) hitCache_.finish();
    stats.shadeMergeMs = msSince(t0);
    // The previous frame's field, resolved once for every lookup of this frame's shading.
    ProbeSampler previous(field);
    std::unique_ptr<OcclusionProbeVisibility> occlusion;
    if (desc.directLight == DdgiDirectLight::OcclusionProbes)
        occlusion = std::make_unique<OcclusionProbeVisibility>(previous, *shadowRays_);
    const LightVisibility& visibility = occlusion ? *occlusion : *shadowRays_;
    ShadeStats shade = shadeProbeRays(tracer_.scene(), visibility, previous, rays_, trace_, blendProbes, frame_,
                                      grouping ? &hitCache_ : nullptr, shaded_, &shadeWorkspace_, sky_);
    stats.cacheGroups = shade.cacheGroups;
    stats.cacheGroupsEvaluated = shade.groupsEvaluated;
    stats.shadeGroupsMs = shade.groupsMs;
    stats.shadeHitsMs = shade.hitsMs;
    stats.cachedHits = shade.cachedHits;
    std::vector<BlendJob> jobs = makeBlendJobs(field, blendProbes, rays_.blendRays);
    if (occlusion) {
        // After shading, so shading reads the previous frame's occlusion (seed 004's lag).
        stats.shadowQueries = updateOcclusionProbes(tracer_.scene(), *shadowRays_, field, rays_, trace_, jobs, frame_,
                                                    desc.occlusionStride);
    } else {
        stats.shadowQueries = shade.shadowQueries;
    }
    stats.shadeMs = msSince(t0);

    blendAndClassify(stats, backend ? *backend : cpuBlend_, blendProbes, jobs);
    return stats;
}

void DdgiSystem::updateElsewhere(DdgiFrameStats& stats, BlendBackend& backend) {
    ProbeField& field = *field_;
    const BlendBackend::UpdateReport counts = backend.updateProbes(field, rays_, frame_);
    stats.traceMs = counts.traceMs;
    stats.blendMs = counts.blendMs;
    stats.borderMs = counts.borderMs;
    stats.classifyMs = counts.classifyMs;
    stats.probesBlended = counts.blended;
    stats.raysTraced = std::int64_t(counts.blended) * rays_.stride() + std::int64_t(counts.fixedOnly) * rays_.fixedRays;
    stats.states = {counts.active, counts.sleeping, counts.off};
    stats.countedFrame = counts.countedFrame;
    if (trackChange_) {
        backend.syncToCpu(field);
        measureChange();
    }
    ++frame_;
}

void DdgiSystem::blendAndClassify(DdgiFrameStats& stats, BlendBackend& blender, const std::vector<int>& blendProbes,
                                  const std::vector<BlendJob>& jobs) {
    ProbeField& field = *field_;
    auto t0 = std::chrono::steady_clock::now();
    blender.blend(field, rays_, shaded_, jobs);
    stats.blendMs = msSince(t0);
    t0 = std::chrono::steady_clock::now();
    blender.border(field, jobs);
    stats.borderMs = msSince(t0);
    for (int p : blendProbes) ++field.probes[std::size_t(p)].blends;

    t0 = std::chrono::steady_clock::now();
    if (field.desc().relocate) relocateProbes(field, rays_, trace_);
    classifyProbes(field, rays_, trace_, query_);
    stats.classifyMs = msSince(t0);
    stats.states = countStates(field);
    stats.countedFrame = std::int64_t(frame_);
    if (trackChange_) {
        blender.syncToCpu(field);
        measureChange();
    }
    ++frame_;
}

void DdgiSystem::measureChange() {
    const ProbeField& field = *field_;
    std::vector<glm::vec3> now(std::size_t(field.probeCount()));
    for (int p = 0; p < field.probeCount(); ++p) now[std::size_t(p)] = field.meanIrradiance(p);
    meanHistory_.push_back(std::move(now));
    if (int(meanHistory_.size()) > kChangeWindow + 1) meanHistory_.pop_front();
    if (int(meanHistory_.size()) <= kChangeWindow) return;
    const std::vector<glm::vec3>&then = meanHistory_.front(), &current = meanHistory_.back();
    double total = 0.0, before = 0.0;
    for (std::size_t p = 0; p < current.size(); ++p) {
        total += double(current[p].x) + double(current[p].y) + double(current[p].z);
        before += double(then[p].x) + double(then[p].y) + double(then[p].z);
    }
    const double moved = std::abs(total - before);
    // A dark field that stays dark has converged; one that went dark has not.
    fieldChange_ = total > 0.0 ? moved / total : (moved > 0.0 ? 1.0 : 0.0);
}

}  // namespace voxgi
