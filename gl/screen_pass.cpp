#include "gl/screen_pass.h"

#include <algorithm>

#include "gl/context.h"
#include "shaders/shared/screen_pass.h"

namespace voxgi::gl {

namespace {

constexpr int kGroupSide = shading::kScreenPassGroupSide;

}  // namespace

void dispatchScreen(const Program& program, ScreenRect rect) {
    if (rect.width <= 0 || rect.height <= 0) return;
    program.use();
    glProgramUniform4i(program.id(), program.location("uScreenRect"), rect.x, rect.y, rect.width, rect.height);
    glDispatchCompute(GLuint((rect.width + kGroupSide - 1) / kGroupSide), GLuint((rect.height + kGroupSide - 1) / kGroupSide), 1);
}

void screenPassBarrier() {
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                    GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
}

void addToBoundTarget(const Program& program, GLuint imageUnit) {
    GLint framebuffer = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    if (framebuffer == 0) throw GlError("addToBoundTarget: the default framebuffer is bound");
    GLint type = GL_NONE, texture = 0;
    glGetNamedFramebufferAttachmentParameteriv(GLuint(framebuffer), GL_COLOR_ATTACHMENT0,
                                               GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
    glGetNamedFramebufferAttachmentParameteriv(GLuint(framebuffer), GL_COLOR_ATTACHMENT0,
                                               GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &texture);
    GLint format = 0;
    if (type == GL_TEXTURE) glGetTextureLevelParameteriv(GLuint(texture), 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    if (format != GL_RGBA32F) throw GlError("addToBoundTarget: the bound target's first attachment is not an RGBA32F texture");
    GLint viewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_VIEWPORT, viewport);
    ScreenRect rect{viewport[0], viewport[1], viewport[2], viewport[3]};
    if (glIsEnabled(GL_SCISSOR_TEST)) {
        GLint box[4] = {0, 0, 0, 0};
        glGetIntegerv(GL_SCISSOR_BOX, box);
        const int x0 = std::max(rect.x, box[0]), y0 = std::max(rect.y, box[1]);
        const int x1 = std::min(rect.x + rect.width, box[0] + box[2]), y1 = std::min(rect.y + rect.height, box[1] + box[3]);
        rect = {x0, y0, std::max(x1 - x0, 0), std::max(y1 - y0, 0)};
    }
    // Draws before this one wrote the target through the framebuffer; the image loads below
    // must see them.
    screenPassBarrier();
    glBindImageTexture(imageUnit, GLuint(texture), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
    glProgramUniform1i(program.id(), program.location("uAdditiveTarget"), GLint(imageUnit));
    dispatchScreen(program, rect);
    screenPassBarrier();
}

}  // namespace voxgi::gl
