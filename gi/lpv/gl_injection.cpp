#include "gi/lpv/gl_injection.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "gi/lpv/gl_cascade_uniforms.h"
#include "gi/sh/sh.h"
#include "gl/program.h"
#include "shaders/shared/constants.h"

namespace voxgi {

GBufferSampling GBufferSampling::of(const GBufferView& g, int target) {
    GBufferSampling s;
    if (target <= 0 || g.width <= 0 || g.height <= 0) return s;
    while (std::max(g.width, g.height) / s.stride > target) s.stride *= 2;
    const int first = s.stride / 2;
    s.columns = first < g.width ? (g.width - first + s.stride - 1) / s.stride : 0;
    s.rows = first < g.height ? (g.height - first + s.stride - 1) / s.stride : 0;
    s.pixel = pixelEdge(g);
    s.forward = viewForward(g.viewProjection);
    return s;
}

GlBlockerVolume::GlBlockerVolume(int resolution) : corners_(resolution + 1) {
    blocker_ = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, corners_, corners_, corners_);
    albedo_ = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, corners_, corners_, corners_);
}

void GlBlockerVolume::upload(const BlockerVolume& volume) {
    const int n = corners_;
    glTextureSubImage3D(blocker_.id(), 0, 0, 0, 0, n, n, n, GL_RGBA, GL_FLOAT, volume.blocker.data());
    std::vector<glm::vec4> albedo4(volume.albedo.size());
    for (std::size_t i = 0; i < albedo4.size(); ++i) albedo4[i] = glm::vec4(volume.albedo[i], 0.0f);
    glTextureSubImage3D(albedo_.id(), 0, 0, 0, 0, n, n, n, GL_RGBA, GL_FLOAT, albedo4.data());
}

struct GlInjector::Impl {
    int n;
    gl::Program light, rsmBlockers, gbufferBlockers, merge;
    gl::Handle vao, lightFbo, scratchFbo;
    GlBlockerVolume scratch;

    explicit Impl(int resolution)
        : n(resolution),
          light(gl::Program::withGeometry("lpv/inject_light.vert", "lpv/inject.geom", "lpv/inject.frag")),
          rsmBlockers(gl::Program::withGeometry("lpv/inject_blocker_rsm.vert", "lpv/inject.geom", "lpv/inject.frag")),
          gbufferBlockers(
              gl::Program::withGeometry("lpv/inject_blocker_gbuffer.vert", "lpv/inject.geom", "lpv/inject.frag")),
          merge(gl::Program::compute("lpv/merge_blockers.comp")), scratch(resolution) {
        vao = gl::createVertexArray();
        lightFbo = gl::createFramebuffer();
        scratchFbo = gl::createFramebuffer();
        const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        glNamedFramebufferDrawBuffers(lightFbo.id(), 3, buffers);
        // Layered attachments: every z slice is a layer the geometry shader can pick.
        glNamedFramebufferTexture(scratchFbo.id(), GL_COLOR_ATTACHMENT0, scratch.blocker(), 0);
        glNamedFramebufferTexture(scratchFbo.id(), GL_COLOR_ATTACHMENT1, scratch.albedo(), 0);
        glNamedFramebufferDrawBuffers(scratchFbo.id(), 2, buffers);
        gl::checkFramebuffer(scratchFbo.id(), "lpv blocker injection");
        const float pi = shading::kPi, a1 = sh::kCosLobe1;
        for (const gl::Program* p : {&light, &rsmBlockers, &gbufferBlockers}) {
            p->set("uShY", glm::vec2(sh::kY00, sh::kY1));
            p->set("uShCosineLobe", glm::vec4(sh::kCosLobe0, a1, a1, a1));
        }
        light.set("uPi", pi);
        merge.set("uShY", glm::vec2(sh::kY00, sh::kY1));
        for (const gl::Program* p : {&rsmBlockers, &gbufferBlockers}) {
            p->set("uFullBlocker", 4.0f / 3.0f);
            p->set("uVolumeSize", n + 1);
        }
        light.set("uVolumeSize", n);
    }

    static void setGrid(const gl::Program& p, const CascadeGrid& grid) {
        p.set("uOrigin", grid.origin);
        p.set("uCellSize", grid.cellSize);
    }

    static void bindTextures(const gl::Program& p, std::initializer_list<std::pair<const char*, GLuint>> textures) {
        GLuint unit = 0;
        for (const auto& [name, texture] : textures) {
            glBindTextureUnit(unit, texture);
            p.set(name, int(unit));
            ++unit;
        }
    }

    // Draws `count` points of `program` into `fbo` (a `size`^3 volume) with additive blending;
    // draw buffer 1 takes the max instead when `maxSecond` (the albedo of blockers).
    void drawPoints(const gl::Program& program, GLuint fbo, int size, int count, bool maxSecond) {
        if (count <= 0) return;
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, size, size);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_PROGRAM_POINT_SIZE);
        glPointSize(1.0f);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        glBlendEquation(GL_FUNC_ADD);
        if (maxSecond) glBlendEquationi(1, GL_MAX);
        program.use();
        glBindVertexArray(vao.id());
        glDrawArrays(GL_POINTS, 0, count);
        glBlendEquation(GL_FUNC_ADD);
        glDisable(GL_BLEND);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }

    void mergeInto(GLuint sourceBlocker, GLuint sourceAlbedo, const GlCascadeTargets& t) {
        merge.use();
        glBindImageTexture(0, t.blocker, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
        glBindImageTexture(1, t.albedo, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA32F);
        bindTextures(merge, {{"uSourceBlocker", sourceBlocker}, {"uSourceAlbedo", sourceAlbedo}});
        merge.set("uSize", n + 1);
        const GLuint groups = GLuint((n + 1 + 3) / 4);
        glDispatchCompute(groups, groups, groups);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                        GL_TEXTURE_UPDATE_BARRIER_BIT);
    }

    void clearScratch() {
        glClearTexImage(scratch.blocker(), 0, GL_RGBA, GL_FLOAT, nullptr);
        glClearTexImage(scratch.albedo(), 0, GL_RGBA, GL_FLOAT, nullptr);
    }
};

GlInjector::GlInjector(int resolution) : impl_(std::make_unique<Impl>(resolution)) {}
GlInjector::~GlInjector() = default;

void GlInjector::clearLight(const GlCascadeTargets& t) {
    for (GLuint texture : t.light) glClearTexImage(texture, 0, GL_RGBA, GL_FLOAT, nullptr);
}

void GlInjector::clearGeometry(const GlCascadeTargets& t) {
    glClearTexImage(t.blocker, 0, GL_RGBA, GL_FLOAT, nullptr);
    glClearTexImage(t.albedo, 0, GL_RGBA, GL_FLOAT, nullptr);
}

void GlInjector::injectLight(const RsmFace& face, const InjectionOffsets& offsets, const GlCascadeTargets& t) {
    impl_->light.set("uShare", 0);
    drawVpls(face, offsets, t);
}

void GlInjector::injectLight(const RsmFace& face, const InjectionOffsets& offsets, const GlCascadeTargets& t,
                             const std::vector<CascadePlacement>& cascades, std::size_t level, bool inner) {
    const gl::Program& p = impl_->light;
    setCascadeUniforms(p, cascades);
    p.set("uShare", inner ? 2 : 1);
    p.set("uLevel", int(level));
    drawVpls(face, offsets, t);
}

void GlInjector::drawVpls(const RsmFace& face, const InjectionOffsets& offsets, const GlCascadeTargets& t) {
    Impl& m = *impl_;
    for (int c = 0; c < 3; ++c)
        glNamedFramebufferTexture(m.lightFbo.id(), GLenum(GL_COLOR_ATTACHMENT0 + c), t.light[c], 0);
    gl::checkFramebuffer(m.lightFbo.id(), "lpv light injection");
    const gl::Program& p = m.light;
    Impl::setGrid(p, t.grid);
    const float h = t.grid.cellSize;
    p.set("uNormalShift", offsets.normalCells * h);
    p.set("uLightShift", offsets.lightCells * h);
    p.set("uSize", face.size);
    p.set("uOrthographic", face.orthographic ? 1 : 0);
    p.set("uLightOrigin", face.origin);
    p.set("uToLight", face.toLight);
    Impl::bindTextures(p, {{"uPosition", face.position}, {"uNormal", face.normal}, {"uFlux", face.flux}});
    m.drawPoints(p, m.lightFbo.id(), m.n, face.size * face.size, false);
}

void GlInjector::injectBlockers(const RsmFace& face, const GlCascadeTargets& t) {
    Impl& m = *impl_;
    m.clearScratch();
    const gl::Program& p = m.rsmBlockers;
    Impl::setGrid(p, t.grid);
    p.set("uFaceArea", t.grid.cellSize * t.grid.cellSize);
    p.set("uSize", face.size);
    Impl::bindTextures(p, {{"uPosition", face.position}, {"uNormal", face.normal}, {"uAlbedo", face.albedo}});
    m.drawPoints(p, m.scratchFbo.id(), m.n + 1, face.size * face.size, true);
    m.mergeInto(m.scratch.blocker(), m.scratch.albedo(), t);
}

void GlInjector::injectBlockers(const GBufferView& g, const GBufferSampling& sampling, const GlCascadeTargets& t) {
    if (sampling.count() <= 0) return;
    Impl& m = *impl_;
    m.clearScratch();
    const gl::Program& p = m.gbufferBlockers;
    Impl::setGrid(p, t.grid);
    p.set("uFaceArea", t.grid.cellSize * t.grid.cellSize);
    p.set("uStride", sampling.stride);
    p.set("uColumns", sampling.columns);
    p.set("uEye", g.eye);
    p.set("uForward", sampling.forward);
    p.set("uPixel", sampling.pixel);
    Impl::bindTextures(
        p, {{"uPosition", g.position}, {"uNormal", g.normal}, {"uAlbedo", g.albedo}, {"uEmission", g.emission}});
    m.drawPoints(p, m.scratchFbo.id(), m.n + 1, sampling.count(), true);
    m.mergeInto(m.scratch.blocker(), m.scratch.albedo(), t);
}

void GlInjector::mergeBlockers(const GlBlockerVolume& source, const GlCascadeTargets& t) {
    impl_->mergeInto(source.blocker(), source.albedo(), t);
}

}  // namespace voxgi
