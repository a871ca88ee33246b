#include "render/view/display_pass.h"

#include "render/view/debug_overlay.h"

#include <algorithm>
#include <cmath>

namespace voxgi::view {

const char* displayModeName(DisplayMode mode) {
    static const char* names[kDisplayModeCount] = {"beauty", "direct", "indirect", "albedo", "normal"};
    return names[int(mode)];
}

DisplayPass::DisplayPass()
    : program_(gl::Program::graphics("frame/fullscreen.vert", "view/display.frag")), vao_(gl::createVertexArray()) {}

void DisplayPass::draw(FrameRenderer& renderer, DisplayMode mode, float exposureStops, int windowWidth,
                       int windowHeight) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glClearColor(0.08f, 0.08f, 0.08f, 1.0f);
    glViewport(0, 0, windowWidth, windowHeight);
    glClear(GL_COLOR_BUFFER_BIT);
    glm::ivec4 box = letterbox(renderer.width(), renderer.height(), windowWidth, windowHeight);
    glViewport(box.x, box.y, box.z, box.w);

    FrameRenderer::Textures t = renderer.textures();
    glBindTextureUnit(0, t.direct);
    glBindTextureUnit(1, t.indirect);
    glBindTextureUnit(2, t.albedo);
    glBindTextureUnit(3, t.normal);
    program_.use();
    int frames = renderer.framesAccumulated();
    program_.set("uInvFrames", frames > 0 ? 1.0f / float(frames) : 0.0f);
    program_.set("uExposureScale", std::exp2(exposureStops));
    program_.set("uMode", int(mode));
    glBindVertexArray(vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glViewport(0, 0, windowWidth, windowHeight);
}

}  // namespace voxgi::view
