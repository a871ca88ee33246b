#include "render/view/display_pass.h"

#include "render/view/debug_overlay.h"

#include <algorithm>
#include <cmath>

#include "shaders/shared/tone_map.h"

namespace voxgi::view {

const char* displayModeName(DisplayMode mode) {
    static const char* names[kDisplayModeCount] = {"beauty", "direct", "indirect", "albedo", "normal"};
    return names[int(mode)];
}

DisplayPass::DisplayPass()
    : program_(gl::Program::graphics("frame/fullscreen.vert", "view/display.frag")),
      logLuminance_(gl::Program::compute("view/log_luminance.comp")),
      result_(gl::createBuffer(2 * sizeof(float), nullptr, GL_DYNAMIC_STORAGE_BIT)),
      vao_(gl::createVertexArray()) {}

std::optional<float> DisplayPass::autoExposureStops(FrameRenderer& renderer, DisplayMode mode) {
    if (mode != DisplayMode::Beauty && mode != DisplayMode::Direct && mode != DisplayMode::Indirect) return std::nullopt;
    const int frames = renderer.framesAccumulated();
    if (frames <= 0) return std::nullopt;
    FrameRenderer::Textures t = renderer.textures();
    glBindTextureUnit(0, t.direct);
    glBindTextureUnit(1, t.indirect);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, result_.id());
    logLuminance_.use();
    logLuminance_.set("uInvFrames", 1.0f / float(frames));
    logLuminance_.set("uMode", int(mode));
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    float sums[2] = {0.0f, 0.0f};
    glGetNamedBufferSubData(result_.id(), 0, sizeof sums, sums);
    if (!(sums[1] > 0.0f)) return std::nullopt;
    const float stops = std::log2(shading::kExposureKey) - sums[0] / sums[1] / std::log(2.0f);
    return std::clamp(stops, -30.0f, 30.0f);
}

void DisplayPass::draw(FrameRenderer& renderer, DisplayMode mode, float exposureStops, int toneCurve, int windowWidth,
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
    program_.set("uToneCurve", toneCurve);
    glBindVertexArray(vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glViewport(0, 0, windowWidth, windowHeight);
}

}  // namespace voxgi::view
