#include "gi/isr/isr_passes.h"

#include <cmath>

namespace voxgi {

IsrPasses::IsrPasses(const IsrDesc& desc)
    : desc_(desc),
      downsample_(gl::Program::graphics("frame/fullscreen.vert", "isr/downsample.frag")),
      gather_program_(gl::Program::graphics("frame/fullscreen.vert", "isr/gather.frag")),
      temporal_(gl::Program::graphics("frame/fullscreen.vert", "isr/temporal.frag")),
      blur_(gl::Program::graphics("frame/fullscreen.vert", "isr/blur.frag")),
      apply_(gl::Program::graphics("frame/fullscreen.vert", "isr/apply.frag")),
      vao_(gl::createVertexArray()) {}

float IsrPasses::radiusPixels() const { return std::max(desc_.radius * float(size_.y), 1.0f); }

void IsrPasses::resize(glm::ivec2 size) {
    if (size == size_) return;
    size_ = size;
    auto target = [&] { return gl::createTexture(GL_TEXTURE_2D, GL_RGBA32F, size.x, size.y); };
    position_ = target();
    normal_ = target();
    radiance_ = target();
    albedo_ = target();
    gather_ = target();
    half_ = target();
    blurred_ = target();
    for (const gl::Handle* t : {&position_, &normal_, &radiance_, &albedo_, &gather_, &half_, &blurred_}) {
        glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    for (int i = 0; i < 2; ++i) {
        mean_[i] = target();
        points_[i] = target();
        normals_[i] = target();
        for (const gl::Handle* t : {&mean_[i], &points_[i], &normals_[i]}) {
            glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
        temporalFbo_[i] = gl::createFramebuffer({mean_[i].id(), points_[i].id(), normals_[i].id()}, 0, "isr temporal mean");
    }
    historyValid_ = false;  // a new size: no history to reproject into
    coarseFbo_ = gl::createFramebuffer({position_.id(), normal_.id(), radiance_.id(), albedo_.id()}, 0, "isr coarse buffers");
    gatherFbo_ = gl::createFramebuffer({gather_.id()}, 0, "isr gather");
    halfFbo_ = gl::createFramebuffer({half_.id()}, 0, "isr blur");
    blurredFbo_ = gl::createFramebuffer({blurred_.id()}, 0, "isr blurred");
}

namespace {

// The far field's light at texture unit `unit` (a texture that is never read stands in without one).
void bindFarLight(gl::Program& program, GLuint unit, GLuint farLight, GLuint fallback) {
    glBindTextureUnit(unit, farLight ? farLight : fallback);
    program.set("uFarLight", int(unit));
    program.set("uHasFarLight", int(farLight != 0));
}

}  // namespace

void IsrPasses::compute(const GBufferView& g, float fovYDegrees, int frame, gl::StageTimers& timers, GLuint farLight) {
    const int f = desc_.downsample;
    resize({(g.width + f - 1) / f, (g.height + f - 1) / f});
    forward_ = viewForward(g.viewProjection);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(vao_.id());
    glViewport(0, 0, size_.x, size_.y);

    timers.begin("isr.downsample");
    glBindFramebuffer(GL_FRAMEBUFFER, coarseFbo_.id());
    downsample_.use();
    const char* names[5] = {"uPosition", "uNormal", "uAlbedo", "uEmission", "uDirectSum"};
    const GLuint textures[5] = {g.position, g.normal, g.albedo, g.emission, g.directSum};
    for (int i = 0; i < 5; ++i) {
        glBindTextureUnit(GLuint(i), textures[i]);
        downsample_.set(names[i], i);
    }
    bindFarLight(downsample_, 5, farLight, g.position);
    // A full-resolution pixel's edge on the image plane at unit distance, times the factor.
    const float edge = 2.0f * std::tan(0.5f * glm::radians(fovYDegrees)) / float(g.height) * float(f);
    downsample_.set("uDirectFrames", float(std::max(g.directFrames, 1)));
    downsample_.set("uFactor", f);
    downsample_.set("uEye", g.eye);
    downsample_.set("uForward", forward_);
    downsample_.set("uPatchSolidAngle", edge * edge);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    timers.end();

    timers.begin("isr.gather");
    glBindFramebuffer(GL_FRAMEBUFFER, gatherFbo_.id());
    gather_program_.use();
    const char* coarse[3] = {"uCoarsePosition", "uCoarseNormal", "uCoarseRadiance"};
    const GLuint coarseTextures[3] = {position_.id(), normal_.id(), radiance_.id()};
    for (int i = 0; i < 3; ++i) {
        glBindTextureUnit(GLuint(i), coarseTextures[i]);
        gather_program_.set(coarse[i], i);
    }
    gather_program_.set("uPatches", desc_.patches);
    gather_program_.set("uRadius", radiusPixels());
    gather_program_.set("uFrame", frame);
    gather_program_.set("uDiscs", int(farLight != 0));
    glDrawArrays(GL_TRIANGLES, 0, 3);
    timers.end();

    if (desc_.temporalFrames > 1) accumulate(g, edge, timers);

    if (desc_.blur > 0) {
        timers.begin("isr.blur");
        blur_.use();
        blur_.set("uRadius", desc_.blur);
        blur_.set("uSource", 0);
        blur_.set("uCoarseNormal", 1);
        glBindTextureUnit(1, normal_.id());
        const GLuint sources[2] = {accumulated(), half_.id()};
        const GLuint targets[2] = {halfFbo_.id(), blurredFbo_.id()};
        for (int pass = 0; pass < 2; ++pass) {
            glBindFramebuffer(GL_FRAMEBUFFER, targets[pass]);
            glBindTextureUnit(0, sources[pass]);
            blur_.set("uStep", glm::ivec2(pass == 0 ? 1 : 0, pass == 0 ? 0 : 1));
            glDrawArrays(GL_TRIANGLES, 0, 3);
        }
        timers.end();
    }
}

void IsrPasses::accumulate(const GBufferView& g, float pixelAngle, gl::StageTimers& timers) {
    timers.begin("isr.temporal");
    const int previous = current_;
    current_ = 1 - current_;
    glBindFramebuffer(GL_FRAMEBUFFER, temporalFbo_[current_].id());
    temporal_.use();
    const char* names[6] = {"uGather", "uCoarsePosition", "uCoarseNormal", "uHistory", "uHistoryPosition", "uHistoryNormal"};
    const GLuint textures[6] = {gather_.id(),       position_.id(),        normal_.id(),
                                mean_[previous].id(), points_[previous].id(), normals_[previous].id()};
    for (int i = 0; i < 6; ++i) {
        glBindTextureUnit(GLuint(i), textures[i]);
        temporal_.set(names[i], i);
    }
    temporal_.set("uPreviousViewProjection", previousViewProjection_);
    temporal_.set("uHistoryValid", historyValid_);
    temporal_.set("uMaxFrames", desc_.temporalFrames);
    temporal_.set("uEye", g.eye);
    temporal_.set("uPixelAngle", pixelAngle);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    previousViewProjection_ = g.viewProjection;
    historyValid_ = true;
    timers.end();
}

void IsrPasses::apply(const GBufferView& g, gl::StageTimers& timers, GLuint farLight) {
    timers.begin("isr.apply");
    apply_.use();
    const char* names[6] = {"uPosition", "uNormal", "uAlbedo", "uEmission", "uCoarseGather", "uCoarseNormal"};
    const GLuint textures[6] = {g.position, g.normal, g.albedo, g.emission, result(), normal_.id()};
    for (int i = 0; i < 6; ++i) {
        glBindTextureUnit(GLuint(i), textures[i]);
        apply_.set(names[i], i);
    }
    bindFarLight(apply_, 6, farLight, g.position);
    apply_.set("uFactor", desc_.downsample);
    apply_.set("uEye", g.eye);
    apply_.set("uForward", forward_);
    apply_.set("uAoStrength", desc_.aoStrength);
    glBindVertexArray(vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    timers.end();
}

}  // namespace voxgi
