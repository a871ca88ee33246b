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
    refill(position, normal, albedo, emission, glm::ivec4(0, 0, view.width, view.height));
}

void UploadedGBuffer::refill(const std::vector<glm::vec4>& position, const std::vector<glm::vec4>& normal,
                             const std::vector<glm::vec4>& albedo, const std::vector<glm::vec4>& emission,
                             glm::ivec4 region) {
    uploadRegion(this->position.id(), view.width, region, position);
    uploadRegion(this->normal.id(), view.width, region, normal);
    uploadRegion(this->albedo.id(), view.width, region, albedo);
    uploadRegion(this->emission.id(), view.width, region, emission);
    const float zero[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 0, zero);
}

void uploadRegion(GLuint texture, int width, glm::ivec4 region, const std::vector<glm::vec4>& data) {
    if (region.z <= 0 || region.w <= 0) return;
    glPixelStorei(GL_UNPACK_ROW_LENGTH, width);
    glTextureSubImage2D(texture, 0, region.x, region.y, region.z, region.w, GL_RGBA, GL_FLOAT,
                        data.data() + std::size_t(region.y) * std::size_t(width) + std::size_t(region.x));
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

glm::ivec4 boundingRegion(glm::ivec4 a, glm::ivec4 b) {
    if (a.z <= 0 || a.w <= 0) return b;
    if (b.z <= 0 || b.w <= 0) return a;
    const glm::ivec2 low = glm::min(glm::ivec2(a), glm::ivec2(b));
    const glm::ivec2 high = glm::max(glm::ivec2(a) + glm::ivec2(a.z, a.w), glm::ivec2(b) + glm::ivec2(b.z, b.w));
    return glm::ivec4(low, high - low);
}

std::vector<float> UploadedGBuffer::readTarget() const {
    return gl::readTexture(target.id(), view.width, view.height, 4);
}

}  // namespace voxgi
