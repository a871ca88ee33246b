#include "gi/isr/isr_technique.h"

namespace voxgi {

IsrTechnique::IsrTechnique(const IsrDesc& desc, std::unique_ptr<GiTechnique> farField)
    : passes_(desc), farField_(std::move(farField)) {}

void IsrTechnique::update(const FrameInput& input, const GBufferView& g) {
    if (farField_) farField_->update(input, g);
}

void IsrTechnique::drawFarField(const FrameInput& input, const GBufferView& g) {
    const glm::ivec2 size(g.width, g.height);
    if (size != farSize_) {
        farSize_ = size;
        farLight_ = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, size.x, size.y);
        glTextureParameteri(farLight_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(farLight_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        farFbo_ = gl::createFramebuffer({farLight_.id()}, 0, "isr far field");
    }
    // As the renderer hands the indirect target to a technique: cleared, additive, full size.
    glBindFramebuffer(GL_FRAMEBUFFER, farFbo_.id());
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 0, zero);
    glViewport(0, 0, size.x, size.y);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    farField_->applyIndirect(input, g);
}

void IsrTechnique::applyIndirect(const FrameInput& input, const GBufferView& g) {
    // No surfaces to bounce between (no triangles): nothing for the far field to light either.
    if (!input.plan.runs("isr.apply")) return;
    // The far field draws into its own target: the renderer's additive target comes back after.
    GLint framebuffer = 0, viewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    glGetIntegerv(GL_VIEWPORT, viewport);
    if (farField_) drawFarField(input, g);
    // With history the kernels keep turning while the camera moves, which restarts frameIndex
    // every frame: the history would otherwise average the same patches again.
    const int turn = passes_.desc().temporalFrames > 1 ? turns_++ : input.frameIndex;
    passes_.compute(g, turn, input.timers, farFieldLight());
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(framebuffer));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    passes_.apply(g, input.timers, farFieldLight());
}

void IsrTechnique::dumpVdb(const std::string& path) const {
    if (farField_) farField_->dumpVdb(path);
    else GiTechnique::dumpVdb(path);
}

std::vector<TechniqueStat> IsrTechnique::stats() const {
    const glm::ivec2 s = passes_.coarseSize();
    std::vector<TechniqueStat> out = {{"isr.coarse_pixels", double(s.x) * double(s.y), "pixels"},
                                      {"isr.radius", double(passes_.radiusPixels()), "coarse pixels"}};
    if (farField_)
        for (const TechniqueStat& stat : farField_->stats()) out.push_back(stat);
    return out;
}

void IsrTechnique::trackConvergence() {
    if (farField_) farField_->trackConvergence();
}

std::optional<double> IsrTechnique::lightStateChange() const {
    return farField_ ? farField_->lightStateChange() : std::nullopt;
}

}  // namespace voxgi
