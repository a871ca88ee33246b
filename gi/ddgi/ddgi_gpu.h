// The GL side of DDGI: the probe atlases as textures, the update kernels (blend.comp,
// border.comp) as a BlendBackend, and the fullscreen apply pass. With CPU ray shading the CPU
// ProbeField stays the master copy: atlases come back after the border pass, because the next
// frame's ray shading reads them on the CPU, and go up before blending only when the CPU
// changed them since. Tracing in the volume (traceInVolume), the whole update runs here
// (schedule.comp, volume_shade.comp, blend, border, classify.comp over indirect dispatches) and
// the atlases and probe records stay on the GPU until a CPU reader asks (syncToCpu).
#pragma once

#include <chrono>
#include <memory>

#include "gi/ddgi/probe_blend.h"
#include "gi/ddgi/volume_shade_gpu.h"
#include "gi/technique.h"
#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {
namespace gl {
class ReadbackRing;
class StageTimers;
}  // namespace gl

class RayTracer;

class DdgiGpu : public BlendBackend {
public:
    explicit DdgiGpu(const ProbeField& field);
    ~DdgiGpu() override;

    // From now on the whole update runs here (ddgi.trace = volume or bvh): the schedule, the
    // blend rays traced and shaded through `geometry` (through `triangles` when given), blend,
    // border, and relocation and classification through the volume, with the probe records
    // kept on the GPU; `scene` gives the lights and must outlive this.
    void traceInVolume(const NanoGeometry& geometry, const Scene& scene, const TriangleBvh* triangles = nullptr);
    // traceInVolume with what ddgi.trace = `trace` (volume or bvh) traces, built for `field`
    // from `tracer`'s scene (the volume by voxelizeForTracing, the BVH by buildTriangleBvh).
    void traceOnGpu(const RayTracer& tracer, const ProbeField& field, DdgiTrace trace);
    bool updatesProbes() const override { return volume_ != nullptr; }
    // The whole update on the GPU. It waits for nothing: its counts (probes per state, blended,
    // fixed-only) are those of the newest update the GPU has finished, read back without a
    // stall a frame or more later (report.countedFrame says which; gl::ReadbackRing), and its
    // stage times are CPU submission times, with the GPU times in the timers given to
    // timeStagesWith. Unless waitForEachStage.
    UpdateReport updateProbes(ProbeField& field, const RaySet& rays, std::uint32_t frame) override;
    // Brackets the GPU update's stages (kDdgiTraceStage...) in the frame's timers (GL_TIME_ELAPSED
    // queries collected with the frame's); null: none.
    void timeStagesWith(gl::StageTimers* timers) { stageTimers_ = timers; }
    // true: the GPU update waits for each stage (glFinish), so its stage times are wall times of
    // the GPU's work (lastTimes: its GPU times) and its counts are this update's. For benchmarks
    // and tests; a frame loses the CPU-GPU overlap.
    void waitForEachStage(bool wait) { waitForEachStage_ = wait; }
    // Where the volume trace finds the sky (VolumeShadeGl::setSky); nothing without it.
    void setSky(bool atMisses, const SkyVolumeTexture* volume) {
        if (volume_) volume_->setSky(atMisses, volume);
    }
    // Tracing in the volume, nothing on the CPU reads the atlases or probe records each frame:
    // they stay on the GPU and this reads them back when they are newer than the CPU's.
    void syncToCpu(ProbeField& field) override;

    void blend(ProbeField& field, const RaySet& rays, const ShadedRays& shaded,
               const std::vector<BlendJob>& jobs) override;
    void border(ProbeField& field, const std::vector<BlendJob>& jobs) override;

    // Uploads both atlases and the per-probe data (offsets, states; with traceInVolume also the
    // blends). blend() and updateProbes() upload the atlases (and updateProbes the records)
    // themselves when the CPU changed them (ProbeField::atlasVersion).
    void upload(const ProbeField& field);
    void uploadProbeData(const ProbeField& field);
    // Draws (1-m)(1-s) albedo/pi * E for every G-buffer pixel into the bound framebuffer.
    void apply(const ProbeField& field, const GBufferView& gbuffer);

    GLuint irradianceTexture() const { return irradiance_.id(); }
    GLuint distanceTexture() const { return distance_.id(); }
    // The last blend's ray values (job * blendRays + ray) and, after updateProbes, its jobs,
    // read back: for tests and diagnostics.
    std::vector<glm::vec4> readRayValues(std::size_t count) const;
    std::vector<BlendJob> readJobs(std::size_t count) const;

    // Where the last blend() and border() spent their time: CPU wall time of the transfers
    // (the atlases and shaded rays going up, the atlases coming back) and GPU time of the
    // kernels (GL_TIME_ELAPSED queries; shadeGpuMs: tracing and shading the rays in the volume).
    struct Times {
        double uploadMs = 0.0, shadeGpuMs = 0.0, blendGpuMs = 0.0, borderGpuMs = 0.0, classifyGpuMs = 0.0,
               readbackMs = 0.0;
        bool atlasesUploaded = false;  // false: the GPU copy was current (no CPU write since)
    };
    const Times& lastTimes() const { return times_; }

private:
    void uploadAtlases(const ProbeField& field);
    void readBack(ProbeField& field);
    // Blend and border over `jobs` jobs, or over the job count of the indirect dispatches
    // (jobs < 0, updateProbes).
    void blendKernels(const ProbeField& field, const RaySet& rays, int jobs);
    // The unrotated blend and fixed directions, uploaded when their counts change.
    void uploadDirections(const RaySet& rays);
    void borderKernels(const ProbeField& field, int jobs);
    // One stage of updateProbes: bracketed by `query` (waitForEachStage) or in stageTimers_.
    std::chrono::steady_clock::time_point beginStage(const char* stage, GLuint query);
    // Its CPU time (the GPU's too when waiting; its GPU time into gpuMs then).
    double endStage(GLuint query, std::chrono::steady_clock::time_point start, double& gpuMs);

    gl::Program blendIrradiance_, blendDistance_, border_, apply_;
    gl::Handle irradiance_, distance_;
    gl::Handle jobs_, directions_, rays_, probeData_;
    std::size_t jobsBytes_ = 0, raysBytes_ = 0, probeDataBytes_ = 0;
    int blendDirectionCount_ = -1, fixedDirectionCount_ = -1;
    gl::Handle blendQuery_, borderQuery_, shadeQuery_, classifyQuery_;
    std::unique_ptr<VolumeShadeGl> volume_;
    // The GPU update's own state (traceInVolume): programs, probe records beside probeData_,
    // this frame's work per probe, the jobs' origins, indirect dispatches and counters.
    gl::Program schedule_, classify_;
    gl::Handle blends_, works_, origins_, dispatches_, counters_, fixedDirections_;
    std::size_t blendsBytes_ = 0, worksBytes_ = 0, originsBytes_ = 0;
    int dispatchRays_ = -1;  // the blend rays the dispatches' fixed sizes were written for
    bool cpuStale_ = false;  // the GPU atlases (and records) are newer than the field's (syncToCpu)
    std::unique_ptr<gl::ReadbackRing> counts_;  // each update's counters, read back later
    UpdateReport lastCounts_;                    // the newest update's counts read so far
    gl::StageTimers* stageTimers_ = nullptr;
    bool waitForEachStage_ = false;
    Times times_;
    // The field (and its atlasVersion) the GPU atlases hold, after an upload or a read-back.
    std::vector<glm::vec4> staging_;  // atlas rows on their way up or down
    const ProbeField* synced_ = nullptr;
    std::uint64_t syncedVersion_ = 0;
};

}  // namespace voxgi
