// Image-space radiosity as a frame technique (`isr`, seed 003): one bounce of the frame's direct
// light between the surfaces on screen, gathered per coarse pixel and upsampled (gi/isr/isr_passes.h).
// It runs in applyIndirect, after the frame's direct light, which its senders reflect.
#pragma once

#include <memory>

#include "gi/isr/isr_desc.h"
#include "gi/isr/isr_passes.h"
#include "gi/technique.h"

namespace voxgi {

class IsrTechnique final : public GiTechnique {
public:
    // Needs a current GL context.
    IsrTechnique(const Scene& scene, const IsrDesc& desc);
    std::string name() const override { return "isr"; }
    void update(const FrameInput&, const GBufferView&) override {}
    void applyIndirect(const FrameInput& input, const GBufferView& g) override;
    std::vector<TechniqueStat> stats() const override;
    const IsrPasses& passes() const { return passes_; }

private:
    const Scene& scene_;
    IsrPasses passes_;
    int turns_ = 0;  // frames drawn, for the kernels' rotation when there is history
};

}  // namespace voxgi
