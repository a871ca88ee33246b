#include "gi/lpv/gl_propagation.h"

#include <array>
#include <string>

#include "render/gl/program.h"
#include "render/gl/resources.h"

namespace voxgi {

struct GlPropagator::Impl {
    int n;
    gl::Program program;
    std::array<gl::Handle, 3> ping, pong, acc;
    gl::Handle blocker, albedo;

    explicit Impl(int resolution) : n(resolution), program(gl::Program::compute("lpv/propagate.comp")) {
        for (int c = 0; c < 3; ++c) {
            ping[std::size_t(c)] = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n, n, n);
            pong[std::size_t(c)] = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n, n, n);
            acc[std::size_t(c)] = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n, n, n);
        }
        blocker = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n + 1, n + 1, n + 1);
        albedo = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n + 1, n + 1, n + 1);
        // Constant tables, shared with the CPU path.
        const PropagationTables& t = propagationTables();
        const PropagationKernel& k = propagationKernel();
        for (int a = 0; a < 6; ++a) {
            std::string ai = "[" + std::to_string(a) + "]";
            program.set(("uAxes" + ai).c_str(), t.axes[std::size_t(a)]);
            program.set(("uUnoccluded" + ai).c_str(), k.unoccluded[std::size_t(a)]);
            for (int f = 0; f < 5; ++f) {
                const FaceCoefficients& fc = k.faces[std::size_t(a)][std::size_t(f)];
                std::string fi = "[" + std::to_string(a * 5 + f) + "]";
                program.set(("uFaceSample" + fi).c_str(), fc.sample);
                program.set(("uFaceBlock" + fi).c_str(), fc.block);
                program.set(("uFaceLobe" + fi).c_str(), fc.lobe);
            }
        }
        program.set("uResolution", n);
    }

    void upload(GLuint texture, const std::vector<glm::vec4>& data, int size) {
        glTextureSubImage3D(texture, 0, 0, 0, 0, size, size, size, GL_RGBA, GL_FLOAT, data.data());
    }
};

GlPropagator::GlPropagator(int resolution) : impl_(std::make_unique<Impl>(resolution)) {}
GlPropagator::~GlPropagator() = default;

void GlPropagator::propagate(const LightVolume& injected, const BlockerVolume& geometry, int steps,
                             const PropagationOptions& options) {
    Impl& m = *impl_;
    const std::vector<glm::vec4>* channels[3] = {&injected.r, &injected.g, &injected.b};
    for (std::size_t c = 0; c < 3; ++c) {
        m.upload(m.ping[c].id(), *channels[c], m.n);
        m.upload(m.acc[c].id(), *channels[c], m.n);
    }
    m.upload(m.blocker.id(), geometry.blocker, m.n + 1);
    std::vector<glm::vec4> albedo4(geometry.albedo.size());
    for (std::size_t i = 0; i < albedo4.size(); ++i) albedo4[i] = glm::vec4(geometry.albedo[i], 0.0f);
    m.upload(m.albedo.id(), albedo4, m.n + 1);
    m.program.use();
    m.program.set("uOcclusion", options.occlusion ? 1 : 0);
    m.program.set("uBounces", options.bounces ? 1 : 0);
    const char* inputs[5] = {"uInR", "uInG", "uInB", "uBlocker", "uAlbedo"};
    for (int i = 0; i < 5; ++i) m.program.set(inputs[i], i);
    glBindTextureUnit(3, m.blocker.id());
    glBindTextureUnit(4, m.albedo.id());
    const GLuint groups = GLuint((m.n + 3) / 4);
    for (int s = 0; s < steps; ++s) {
        for (std::size_t c = 0; c < 3; ++c) {
            glBindTextureUnit(GLuint(c), m.ping[c].id());
            glBindImageTexture(GLuint(c), m.pong[c].id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
            glBindImageTexture(GLuint(3 + c), m.acc[c].id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
        }
        glDispatchCompute(groups, groups, groups);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        std::swap(m.ping, m.pong);
    }
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
}

GLuint GlPropagator::accumulated(int channel) const { return impl_->acc[std::size_t(channel)].id(); }

void GlPropagator::readBack(LightVolume& out) const {
    const int n = impl_->n;
    std::vector<glm::vec4>* channels[3] = {&out.r, &out.g, &out.b};
    for (int c = 0; c < 3; ++c) {
        channels[c]->resize(std::size_t(n) * std::size_t(n) * std::size_t(n));
        glGetTextureImage(impl_->acc[std::size_t(c)].id(), 0, GL_RGBA, GL_FLOAT,
                          GLsizei(channels[c]->size() * sizeof(glm::vec4)), channels[c]->data());
    }
}

}  // namespace voxgi
