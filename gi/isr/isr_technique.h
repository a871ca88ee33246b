// Image-space radiosity as a frame technique (`isr`, seed 003): one bounce of the frame's direct
// light between the surfaces on screen, gathered per coarse pixel and upsampled (gi/isr/isr_passes.h).
// It runs in applyIndirect, after the frame's direct light, which its senders reflect. With a far
// field (isr.far_field) it also runs that volume method: the volume's indirect light goes into a
// texture of its own, which the patches send on and which fills what the screen leaves open.
#pragma once

#include <memory>

#include "gi/isr/isr_desc.h"
#include "gi/isr/isr_passes.h"
#include "gi/technique.h"

namespace voxgi {

class IsrTechnique final : public GiTechnique {
public:
    // Needs a current GL context. `farField`: the technique of desc.farField, or null for none.
    explicit IsrTechnique(const IsrDesc& desc, std::unique_ptr<GiTechnique> farField = nullptr);
    std::string name() const override { return "isr"; }
    void update(const FrameInput& input, const GBufferView& g) override;
    void applyIndirect(const FrameInput& input, const GBufferView& g) override;
    void dumpVdb(const std::string& path) const override;
    std::vector<TechniqueStat> stats() const override;
    void trackConvergence() override;
    std::optional<double> lightStateChange() const override;
    const IsrPasses& passes() const { return passes_; }
    // The far field's indirect radiance this frame (RGBA32F, the G-buffer's size); 0 without one.
    GLuint farFieldLight() const { return farField_ ? farLight_.id() : 0; }

private:
    void drawFarField(const FrameInput& input, const GBufferView& g);

    IsrPasses passes_;
    std::unique_ptr<GiTechnique> farField_;
    gl::Handle farLight_, farFbo_;
    glm::ivec2 farSize_{0};
    int turns_ = 0;  // frames drawn, for the kernels' rotation when there is history
};

}  // namespace voxgi
