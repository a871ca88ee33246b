// The GL side of DDGI: the probe atlases as textures, the update kernels (blend.comp,
// border.comp) as a BlendBackend, and the fullscreen apply pass. The CPU ProbeField stays the
// master copy: atlases go up before blending and come back after the border pass, because the
// next frame's ray shading reads them on the CPU.
#pragma once

#include "gi/ddgi/probe_blend.h"
#include "gi/technique.h"
#include "render/gl/program.h"
#include "render/gl/resources.h"

namespace voxgi {

class DdgiGpu : public BlendBackend {
public:
    explicit DdgiGpu(const ProbeField& field);

    void blend(ProbeField& field, const RaySet& rays, const ShadedRays& shaded,
               const std::vector<BlendJob>& jobs) override;
    void border(ProbeField& field, const std::vector<BlendJob>& jobs) override;

    // Uploads both atlases and the per-probe data (offsets, states).
    void upload(const ProbeField& field);
    void uploadProbeData(const ProbeField& field);
    // Draws (1-m)(1-s) albedo/pi * E for every G-buffer pixel into the bound framebuffer.
    void apply(const ProbeField& field, const GBufferView& gbuffer);

    GLuint irradianceTexture() const { return irradiance_.id(); }
    GLuint distanceTexture() const { return distance_.id(); }

private:
    void readBack(ProbeField& field);
    void ensureBuffer(gl::Handle& buffer, std::size_t& capacity, std::size_t bytes);

    gl::Program blendIrradiance_, blendDistance_, border_, apply_;
    gl::Handle irradiance_, distance_, emptyVao_;
    gl::Handle jobs_, directions_, rays_, probeData_;
    std::size_t jobsBytes_ = 0, directionsBytes_ = 0, raysBytes_ = 0, probeDataBytes_ = 0;
};

}  // namespace voxgi
