// The GL side of DDGI: the probe atlases as textures, the update kernels (blend.comp,
// border.comp) as a BlendBackend, and the fullscreen apply pass. With CPU ray shading the CPU
// ProbeField stays the master copy: atlases come back after the border pass, because the next
// frame's ray shading reads them on the CPU, and go up before blending only when the CPU
// changed them since. Tracing in the volume (traceInVolume), they stay on the GPU until a CPU
// reader asks (syncToCpu).
#pragma once

#include <memory>

#include "gi/ddgi/probe_blend.h"
#include "gi/ddgi/volume_shade_gpu.h"
#include "gi/technique.h"
#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {

class DdgiGpu : public BlendBackend {
public:
    explicit DdgiGpu(const ProbeField& field);
    ~DdgiGpu() override;

    // From now on the blend rays are traced and shaded here, through `geometry` (ddgi.trace =
    // volume); `scene` gives the lights and must outlive this.
    void traceInVolume(const NanoGeometry& geometry, const Scene& scene);
    bool shadesRays() const override { return volume_ != nullptr; }
    // Where the volume trace finds the sky (VolumeShadeGl::setSky); nothing without it.
    void setSky(bool atMisses, const SkyVolumeTexture* volume) {
        if (volume_) volume_->setSky(atMisses, volume);
    }
    // Tracing in the volume, nothing on the CPU reads the atlases each frame: border() leaves
    // them on the GPU and this reads them back when they are newer than the CPU's.
    void syncToCpu(ProbeField& field) override;
    void shadeRays(const RaySet& rays, const ProbeTrace& trace, const std::vector<BlendJob>& jobs,
                   std::uint32_t frame) override;

    void blend(ProbeField& field, const RaySet& rays, const ShadedRays& shaded,
               const std::vector<BlendJob>& jobs) override;
    void border(ProbeField& field, const std::vector<BlendJob>& jobs) override;

    // Uploads both atlases and the per-probe data (offsets, states). blend() uploads the
    // atlases itself when the CPU changed them (ProbeField::atlasVersion).
    void upload(const ProbeField& field);
    void uploadProbeData(const ProbeField& field);
    // Draws (1-m)(1-s) albedo/pi * E for every G-buffer pixel into the bound framebuffer.
    void apply(const ProbeField& field, const GBufferView& gbuffer);

    GLuint irradianceTexture() const { return irradiance_.id(); }
    // The last blend's ray values (job * blendRays + ray), read back: for tests and diagnostics.
    std::vector<glm::vec4> readRayValues(std::size_t count) const;
    GLuint distanceTexture() const { return distance_.id(); }

    // Where the last blend() and border() spent their time: CPU wall time of the transfers
    // (the atlases and shaded rays going up, the atlases coming back) and GPU time of the
    // kernels (GL_TIME_ELAPSED queries; shadeGpuMs: tracing and shading the rays in the volume).
    struct Times {
        double uploadMs = 0.0, shadeGpuMs = 0.0, blendGpuMs = 0.0, borderGpuMs = 0.0, readbackMs = 0.0;
        bool atlasesUploaded = false;  // false: the GPU copy was current (no CPU write since)
    };
    const Times& lastTimes() const { return times_; }

private:
    void uploadAtlases(const ProbeField& field);
    void readBack(ProbeField& field);

    gl::Program blendIrradiance_, blendDistance_, border_, apply_;
    gl::Handle irradiance_, distance_;
    gl::Handle jobs_, directions_, rays_, probeData_;
    std::size_t jobsBytes_ = 0, directionsBytes_ = 0, raysBytes_ = 0, probeDataBytes_ = 0;
    gl::Handle blendQuery_, borderQuery_, shadeQuery_;
    std::unique_ptr<VolumeShadeGl> volume_;
    bool shadePending_ = false;  // shadeRays() prepared this frame's rays for blend()
    bool cpuStale_ = false;      // the GPU atlases are newer than the field's (syncToCpu)
    Times times_;
    // The field (and its atlasVersion) the GPU atlases hold, after an upload or a read-back.
    std::vector<glm::vec4> staging_;  // atlas rows on their way up or down
    const ProbeField* synced_ = nullptr;
    std::uint64_t syncedVersion_ = 0;
};

}  // namespace voxgi
