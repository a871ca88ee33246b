#include "gi/gbuffer_upload.h"

namespace voxgi {

namespace {
void fill(const gl::Handle& t, const std::vector<glm::vec4>& data, int width, int height) {
    glTextureSubImage2D(t.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, data.data());
}
gl::Handle rgba32f(const std::vector<glm::vec4>& data, int width, int height) {
    gl::Handle t = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
    fill(t, data, width, height);
    return t;
}
}  // namespace

UploadedGBuffer uploadGBuffer(const std::vector<glm::vec4>& position, const std::vector<glm::vec4>& normal,
                              const std::vector<glm::vec4>& albedo, const std::vector<glm::vec4>& emission,
                              int width, int height, glm::vec3 eye) {
    UploadedGBuffer g;
    g.position = rgba32f(position, width, height);
    g.normal = rgba32f(normal, width, height);
    g.albedo = rgba32f(albedo, width, height);
    g.emission = rgba32f(emission, width, height);
    g.target = gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, width, height);
    g.framebuffer = gl::createFramebuffer({g.target.id()}, 0, "uploaded G-buffer target");
    glBindFramebuffer(GL_FRAMEBUFFER, g.framebuffer.id());
    glViewport(0, 0, width, height);
    const float zero[4] = {0, 0, 0, 0};
    glClearBufferfv(GL_COLOR, 0, zero);
    g.view.position = g.position.id();
    g.view.normal = g.normal.id();
    g.view.albedo = g.albedo.id();
    g.view.emission = g.emission.id();
    g.view.width = width;
    g.view.height = height;
    g.view.eye = eye;
    return g;
}

void UploadedGBuffer::refill(const std::vector<glm::vec4>& position, const std::vector<glm::vec4>& normal,
                             const std::vector<glm::vec4>& albedo, const std::vector<glm::vec4>& emission) {
    fill(this->position, position, view.width, view.height);
    fill(this->normal, normal, view.width, view.height);
    fill(this->albedo, albedo, view.width, view.height);
    fill(this->emission, emission, view.width, view.height);
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 0, zero);
}

std::vector<float> UploadedGBuffer::readTarget() const {
    return gl::readTexture(target.id(), view.width, view.height, 4);
}

}  // namespace voxgi
