#include "gi/isr/isr_passes.h"

#include <cmath>

#include "gl/screen_pass.h"

namespace voxgi {

IsrPasses::IsrPasses(const IsrDesc& desc)
    : desc_(desc),
      downsample_(gl::Program::compute("isr/downsample.comp")),
      gather_program_(gl::Program::compute("isr/gather.comp")),
      temporal_(gl::Program::compute("isr/temporal.comp")),
      blur_(gl::Program::compute("isr/blur.comp")),
      apply_(gl::Program::compute("isr/apply.comp")) {}

float IsrPasses::radiusPixels() const { return std::max(desc_.radius * pictureHeight_, 1.0f); }

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
    }
    historyValid_ = false;  // a new size: no history to reproject into
}

namespace {

// The far field's light at texture unit `unit` (a texture that is never read stands in without one).
void bindFarLight(gl::Program& program, GLuint unit, GLuint farLight, GLuint fallback) {
    glBindTextureUnit(unit, farLight ? farLight : fallback);
    program.set("uFarLight", int(unit));
    program.set("uHasFarLight", int(farLight != 0));
}

// The pass's outputs: image `names[i]` on image unit i, written whole.
void bindOutputs(const gl::Program& program, std::initializer_list<std::pair<const char*, GLuint>> outputs) {
    GLuint unit = 0;
    for (const auto& [name, texture] : outputs) {
        glBindImageTexture(unit, texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        program.set(name, int(unit));
        ++unit;
    }
}

}  // namespace

void IsrPasses::compute(const GBufferView& g, int frame, gl::StageTimers& timers, GLuint farLight) {
    const int f = desc_.downsample;
    resize({(g.width + f - 1) / f, (g.height + f - 1) / f});
    // The disc is a fraction of the picture: a guard band (a larger G-buffer around it) adds the
    // senders beyond the picture's edges without widening every pixel's disc.
    pictureHeight_ = float((g.height - 2 * g.pictureOrigin.y + f - 1) / f);
    forward_ = viewForward(g.viewProjection);
    const gl::ScreenRect coarse{0, 0, size_.x, size_.y};
    // The direct layer (and a far field) were drawn just now; the passes below fetch them.
    gl::screenPassBarrier();

    timers.begin("isr.downsample");
    bindOutputs(downsample_, {{"uOutPosition", position_.id()}, {"uOutNormal", normal_.id()},
                              {"uOutRadiance", radiance_.id()}, {"uOutAlbedo", albedo_.id()}});
    const char* names[5] = {"uPosition", "uNormal", "uAlbedo", "uEmission", "uDirectSum"};
    const GLuint textures[5] = {g.position, g.normal, g.albedo, g.emission, g.directSum};
    for (int i = 0; i < 5; ++i) {
        glBindTextureUnit(GLuint(i), textures[i]);
        downsample_.set(names[i], i);
    }
    bindFarLight(downsample_, 5, farLight, g.position);
    // A full-resolution pixel's edge on the image plane at unit distance, times the factor.
    const float edge = pixelEdge(g) * float(f);
    downsample_.set("uDirectFrames", float(std::max(g.directFrames, 1)));
    downsample_.set("uFactor", f);
    downsample_.set("uEye", g.eye);
    downsample_.set("uForward", forward_);
    downsample_.set("uPatchSolidAngle", edge * edge);
    gl::dispatchScreen(downsample_, coarse);
    gl::screenPassBarrier();
    timers.end();

    timers.begin("isr.gather");
    bindOutputs(gather_program_, {{"uOutGather", gather_.id()}});
    const char* coarseNames[3] = {"uCoarsePosition", "uCoarseNormal", "uCoarseRadiance"};
    const GLuint coarseTextures[3] = {position_.id(), normal_.id(), radiance_.id()};
    for (int i = 0; i < 3; ++i) {
        glBindTextureUnit(GLuint(i), coarseTextures[i]);
        gather_program_.set(coarseNames[i], i);
    }
    gather_program_.set("uPatches", desc_.patches);
    gather_program_.set("uRadius", radiusPixels());
    gather_program_.set("uFrame", frame);
    gather_program_.set("uDiscs", int(farLight != 0));
    gl::dispatchScreen(gather_program_, coarse);
    gl::screenPassBarrier();
    timers.end();

    if (desc_.temporalFrames > 1) accumulate(g, edge, timers);

    if (desc_.blur > 0) {
        timers.begin("isr.blur");
        blur_.set("uRadius", desc_.blur);
        blur_.set("uSource", 0);
        blur_.set("uCoarseNormal", 1);
        glBindTextureUnit(1, normal_.id());
        const GLuint sources[2] = {accumulated(), half_.id()};
        const GLuint targets[2] = {half_.id(), blurred_.id()};
        for (int pass = 0; pass < 2; ++pass) {
            bindOutputs(blur_, {{"uOutBlurred", targets[pass]}});
            glBindTextureUnit(0, sources[pass]);
            blur_.set("uStep", glm::ivec2(pass == 0 ? 1 : 0, pass == 0 ? 0 : 1));
            gl::dispatchScreen(blur_, coarse);
            gl::screenPassBarrier();
        }
        timers.end();
    }
}

void IsrPasses::accumulate(const GBufferView& g, float pixelAngle, gl::StageTimers& timers) {
    timers.begin("isr.temporal");
    const int previous = current_;
    current_ = 1 - current_;
    bindOutputs(temporal_, {{"uOutMean", mean_[current_].id()}, {"uOutPosition", points_[current_].id()},
                            {"uOutNormal", normals_[current_].id()}});
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
    gl::dispatchScreen(temporal_, {0, 0, size_.x, size_.y});
    gl::screenPassBarrier();
    previousViewProjection_ = g.viewProjection;
    historyValid_ = true;
    timers.end();
}

void IsrPasses::apply(const GBufferView& g, gl::StageTimers& timers, GLuint farLight) {
    timers.begin("isr.apply");
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
    gl::addToBoundTarget(apply_);
    timers.end();
}

}  // namespace voxgi
