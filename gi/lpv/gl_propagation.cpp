#include "gi/lpv/gl_propagation.h"

#include <algorithm>
#include <array>
#include <vector>
#include <string>

#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {

struct GlPropagator::Impl {
    // One light volume's textures (r, g, b each).
    struct LightSet {
        std::array<gl::Handle, 3> injected, ping, pong, acc;
    };
    int n;
    gl::Program program, faceProgram;
    std::vector<LightSet> sets;
    gl::Handle blocker, albedo;
    // Every face's blocker and albedo (lpv/face_blockers.comp), the faces of axis k at x offset
    // k (n + 1): made once per update, read by every step.
    gl::Handle faceBlocker, faceAlbedo;

    Impl(int resolution, int lightSets)
        : n(resolution),
          program(gl::Program::compute("lpv/propagate.comp")),
          faceProgram(gl::Program::compute("lpv/face_blockers.comp")),
          sets(std::size_t(lightSets)) {
        for (LightSet& s : sets)
            for (std::size_t c = 0; c < 3; ++c) {
                s.injected[c] = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n, n, n);
                s.ping[c] = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n, n, n);
                s.pong[c] = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n, n, n);
                s.acc[c] = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n, n, n);
            }
        blocker = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n + 1, n + 1, n + 1);
        albedo = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, n + 1, n + 1, n + 1);
        faceBlocker = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, 3 * (n + 1), n + 1, n + 1);
        faceAlbedo = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, 3 * (n + 1), n + 1, n + 1);
        faceProgram.set("uResolution", n);
        faceProgram.set("uBlocker", 0);
        faceProgram.set("uAlbedo", 1);
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

    void copy(GLuint from, GLuint to) const {
        glCopyImageSubData(from, GL_TEXTURE_3D, 0, 0, 0, 0, to, GL_TEXTURE_3D, 0, 0, 0, 0, n, n, n);
    }
};

namespace {
void readVolume(GLuint texture, int size, std::vector<glm::vec4>& out) {
    out.resize(std::size_t(size) * std::size_t(size) * std::size_t(size));
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(out.size() * sizeof(glm::vec4)), out.data());
}
}  // namespace

GlPropagator::GlPropagator(int resolution, int lightSets)
    : impl_(std::make_unique<Impl>(resolution, std::max(lightSets, 1))) {}
GlPropagator::~GlPropagator() = default;

int GlPropagator::resolution() const { return impl_->n; }
int GlPropagator::lightSets() const { return int(impl_->sets.size()); }

void GlPropagator::propagate(const LightVolume& injected, const BlockerVolume& geometry, int steps,
                             const PropagationOptions& options) {
    Impl& m = *impl_;
    const std::vector<glm::vec4>* channels[3] = {&injected.r, &injected.g, &injected.b};
    for (std::size_t c = 0; c < 3; ++c) m.upload(m.sets[0].injected[c].id(), *channels[c], m.n);
    m.upload(m.blocker.id(), geometry.blocker, m.n + 1);
    std::vector<glm::vec4> albedo4(geometry.albedo.size());
    for (std::size_t i = 0; i < albedo4.size(); ++i) albedo4[i] = glm::vec4(geometry.albedo[i], 0.0f);
    m.upload(m.albedo.id(), albedo4, m.n + 1);
    propagateInjected(steps, options);
}

void GlPropagator::propagateInjected(int steps, const PropagationOptions& options) {
    Impl& m = *impl_;
    // Writes through framebuffers or images (GlInjector) must land before the copies read them.
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);
    const GLuint groups = GLuint((m.n + 3) / 4);
    if (options.occlusion) {
        m.faceProgram.use();
        glBindTextureUnit(0, m.blocker.id());
        glBindTextureUnit(1, m.albedo.id());
        glBindImageTexture(0, m.faceBlocker.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindImageTexture(1, m.faceAlbedo.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        const GLuint cornerGroups = GLuint((m.n + 1 + 3) / 4);
        glDispatchCompute(GLuint((3 * (m.n + 1) + 3) / 4), cornerGroups, cornerGroups);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    m.program.use();
    m.program.set("uOcclusion", options.occlusion ? 1 : 0);
    m.program.set("uBounces", options.bounces ? 1 : 0);
    const char* inputs[5] = {"uInR", "uInG", "uInB", "uFaceBlocker", "uFaceAlbedo"};
    for (int i = 0; i < 5; ++i) m.program.set(inputs[i], i);
    glBindTextureUnit(3, m.faceBlocker.id());
    glBindTextureUnit(4, m.faceAlbedo.id());
    for (Impl::LightSet& set : m.sets) {
        for (std::size_t c = 0; c < 3; ++c) {
            m.copy(set.injected[c].id(), set.ping[c].id());
            m.copy(set.injected[c].id(), set.acc[c].id());
        }
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        for (int s = 0; s < steps; ++s) {
            for (std::size_t c = 0; c < 3; ++c) {
                glBindTextureUnit(GLuint(c), set.ping[c].id());
                glBindImageTexture(GLuint(c), set.pong[c].id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
                glBindImageTexture(GLuint(3 + c), set.acc[c].id(), 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
            }
            glDispatchCompute(groups, groups, groups);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            std::swap(set.ping, set.pong);
        }
    }
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
}

GLuint GlPropagator::injected(int channel, int set) const {
    return impl_->sets[std::size_t(set)].injected[std::size_t(channel)].id();
}
GLuint GlPropagator::blocker() const { return impl_->blocker.id(); }
GLuint GlPropagator::albedo() const { return impl_->albedo.id(); }

GLuint GlPropagator::accumulated(int channel, int set) const {
    return impl_->sets[std::size_t(set)].acc[std::size_t(channel)].id();
}

void GlPropagator::readBack(LightVolume& out, int set) const {
    for (std::size_t c = 0; c < 3; ++c)
        readVolume(accumulated(int(c), set), impl_->n, c == 0 ? out.r : (c == 1 ? out.g : out.b));
}

void GlPropagator::readBackInjected(LightVolume& out, int set) const {
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    for (std::size_t c = 0; c < 3; ++c)
        readVolume(injected(int(c), set), impl_->n, c == 0 ? out.r : (c == 1 ? out.g : out.b));
}

void GlPropagator::readBackGeometry(BlockerVolume& out) const {
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    readVolume(impl_->blocker.id(), impl_->n + 1, out.blocker);
    std::vector<glm::vec4> albedo4;
    readVolume(impl_->albedo.id(), impl_->n + 1, albedo4);
    out.albedo.resize(albedo4.size());
    for (std::size_t i = 0; i < albedo4.size(); ++i) out.albedo[i] = glm::vec3(albedo4[i]);
}

}  // namespace voxgi
