#include "gl/resources.h"

#include <algorithm>
#include <string>

#include "gl/context.h"

namespace voxgi::gl {

Handle createTexture(GLenum target, GLenum internalFormat, int width, int height, int depth, int levels) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    if (target == GL_TEXTURE_3D || target == GL_TEXTURE_2D_ARRAY || target == GL_TEXTURE_CUBE_MAP_ARRAY)
        glTextureStorage3D(id, levels, internalFormat, width, height, depth);
    else
        glTextureStorage2D(id, levels, internalFormat, width, height);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    return Handle(id, [](GLuint i) { glDeleteTextures(1, &i); });
}

Handle createBuffer(std::size_t bytes, const void* data, GLbitfield flags) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    glNamedBufferStorage(id, GLsizeiptr(bytes > 0 ? bytes : 4), data, flags);
    return Handle(id, [](GLuint i) { glDeleteBuffers(1, &i); });
}

Handle createFramebuffer() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return Handle(id, [](GLuint i) { glDeleteFramebuffers(1, &i); });
}

Handle createVertexArray() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return Handle(id, [](GLuint i) { glDeleteVertexArrays(1, &i); });
}

Handle createSampler() {
    GLuint id = 0;
    glCreateSamplers(1, &id);
    return Handle(id, [](GLuint i) { glDeleteSamplers(1, &i); });
}

Handle createTimerQuery() {
    GLuint id = 0;
    glCreateQueries(GL_TIME_ELAPSED, 1, &id);
    return Handle(id, [](GLuint i) { glDeleteQueries(1, &i); });
}

void ensureBuffer(Handle& buffer, std::size_t& capacity, std::size_t bytes, double growth) {
    bytes = std::max<std::size_t>(bytes, 16);
    if (buffer && capacity >= bytes) return;
    capacity = std::max(bytes, std::size_t(double(bytes) * growth));
    buffer = createBuffer(capacity, nullptr, GL_DYNAMIC_STORAGE_BIT);
}

double timerQueryMs(GLuint query) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    return double(ns) * 1e-6;
}

Handle createFramebuffer(std::initializer_list<GLuint> colors, GLuint depth, const char* what) {
    Handle fbo = createFramebuffer();
    std::vector<GLenum> buffers;
    for (GLuint texture : colors) {
        GLenum attachment = GL_COLOR_ATTACHMENT0 + GLenum(buffers.size());
        glNamedFramebufferTexture(fbo.id(), attachment, texture, 0);
        buffers.push_back(attachment);
    }
    if (depth) glNamedFramebufferTexture(fbo.id(), GL_DEPTH_ATTACHMENT, depth, 0);
    if (buffers.empty()) glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
    else glNamedFramebufferDrawBuffers(fbo.id(), GLsizei(buffers.size()), buffers.data());
    checkFramebuffer(fbo.id(), what);
    return fbo;
}

void checkFramebuffer(GLuint framebuffer, const char* what) {
    GLenum status = glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw GlError(std::string(what) + ": framebuffer incomplete (status 0x" + std::to_string(status) + ")");
}

std::vector<float> readTexture(GLuint texture, int width, int height, int channels) {
    std::vector<float> out(std::size_t(width) * std::size_t(height) * std::size_t(channels));
    GLenum format = channels == 1 ? GL_RED : channels == 3 ? GL_RGB : GL_RGBA;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(texture, 0, format, GL_FLOAT, GLsizei(out.size() * sizeof(float)), out.data());
    return out;
}

}  // namespace voxgi::gl
