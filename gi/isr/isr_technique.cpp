#include "gi/isr/isr_technique.h"

namespace voxgi {

IsrTechnique::IsrTechnique(const Scene& scene, const IsrDesc& desc) : scene_(scene), passes_(desc) {}

void IsrTechnique::applyIndirect(const FrameInput& input, const GBufferView& g) {
    if (!input.plan.runs("isr.apply")) return;
    // compute() draws into its own coarse targets: the renderer's additive target comes back after.
    GLint framebuffer = 0, viewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    glGetIntegerv(GL_VIEWPORT, viewport);
    // With history the kernels keep turning while the camera moves, which restarts frameIndex
    // every frame: the history would otherwise average the same patches again.
    const int turn = passes_.desc().temporalFrames > 1 ? turns_++ : input.frameIndex;
    passes_.compute(g, scene_.camera.fovYDegrees, turn, input.timers);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(framebuffer));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    passes_.apply(g, input.timers);
}

std::vector<TechniqueStat> IsrTechnique::stats() const {
    const glm::ivec2 s = passes_.coarseSize();
    return {{"isr.coarse_pixels", double(s.x) * double(s.y), "pixels"},
            {"isr.radius", double(passes_.radiusPixels()), "coarse pixels"}};
}

}  // namespace voxgi
