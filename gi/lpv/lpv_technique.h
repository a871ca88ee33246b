// Light propagation volumes as a frame technique: `lpv` (one volume around the scene) and
// `clpv` (camera-centred cascades). Per frame: reflective shadow maps -> light and blocker
// injection -> propagation (CPU reference or GL compute) -> deferred apply. Nothing is redone
// while the lights, geometry and cascade placement stay the same.
#pragma once

#include <memory>

#include "gi/lpv/lpv_desc.h"
#include "gi/lpv/surfels.h"
#include "gi/technique.h"

namespace voxgi {

class LpvTechnique final : public GiTechnique {
public:
    LpvTechnique(const Scene& scene, const LpvDesc& desc, bool cascaded);
    ~LpvTechnique() override;

    std::string name() const override;
    void update(const FrameInput& input, const GBufferView& gbuffer) override;
    void applyIndirect(const FrameInput& input, const GBufferView& gbuffer) override;
    void dumpVdb(const std::string& path) const override;

    const LpvDesc& desc() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The camera's blocker source on the CPU back end: the G-buffer read back and sampled as
// GBufferSampling (gi/lpv/gl_injection.h) says, each pixel a surfel of its footprint's area.
SurfelSource gbufferSurfels(const GBufferView& g, const Camera& camera, int target);

std::unique_ptr<GiTechnique> createLpv(const Scene& scene);
std::unique_ptr<GiTechnique> createClpv(const Scene& scene);

}  // namespace voxgi
