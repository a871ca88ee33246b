// Image-space radiosity's GPU passes (seed 003; shaders/isr/): downsample the G-buffer and the
// frame's direct light into coarse patches, gather one bounce and the sphere occlusion per
// coarse pixel, blur, and upsample into the indirect layer. The coarse buffers stay readable for
// the CPU reference (gi/isr/isr_reference.h) and the tests.
#pragma once

#include <glm/glm.hpp>

#include "gi/isr/isr_desc.h"
#include "gi/technique.h"
#include "gl/program.h"
#include "gl/resources.h"

namespace voxgi {

class IsrPasses {
public:
    // Needs a current GL context.
    explicit IsrPasses(const IsrDesc& desc);

    // Downsample, gather and blur for G-buffer `g` (with its direct light: g.directSum, and the
    // field of view it was drawn with: g.fovYDegrees), kernels turned for `frame`. With a
    // far field (`farLight`, its indirect radiance per G-buffer pixel; 0: none) the patches send
    // that light on with their direct light.
    void compute(const GBufferView& g, int frame, gl::StageTimers& timers, GLuint farLight = 0);
    // Adds the indirect radiance of every G-buffer pixel to the framebuffer bound now (the
    // renderer's additive target, gl::addToBoundTarget), and the far field's where the patches
    // leave the hemisphere open (1 - occlusion).
    void apply(const GBufferView& g, gl::StageTimers& timers, GLuint farLight = 0);

    const IsrDesc& desc() const { return desc_; }
    glm::ivec2 coarseSize() const { return size_; }
    float radiusPixels() const;  // the gather disc's radius in coarse pixels
    // Coarse textures (RGBA32F, coarseSize()): position (w hit), normal (w depth along the
    // camera's axis), radiance (w patch area), the raw gather (rgb irradiance, w occlusion) and
    // what apply reads (the blurred gather, or the raw one without blur).
    GLuint position() const { return position_.id(); }
    GLuint normal() const { return normal_.id(); }
    GLuint radiance() const { return radiance_.id(); }
    GLuint gather() const { return gather_.id(); }
    // The gather averaged over frames (isr.temporal_frames > 1), else the gather itself.
    GLuint accumulated() const { return desc_.temporalFrames > 1 ? mean_[current_].id() : gather_.id(); }
    GLuint result() const { return desc_.blur > 0 ? blurred_.id() : accumulated(); }
    // The surface points behind accumulated(): xyz, w the gathers in each pixel's mean.
    GLuint accumulatedPoints() const { return points_[current_].id(); }

private:
    void resize(glm::ivec2 size);
    void accumulate(const GBufferView& g, float pixelAngle, gl::StageTimers& timers);

    IsrDesc desc_;
    gl::Program downsample_, gather_program_, temporal_, blur_, apply_;
    glm::ivec2 size_{0};
    float pictureHeight_ = 0.0f;  // coarse pixels: the picture's, without a guard band
    gl::Handle position_, normal_, radiance_, albedo_, gather_, half_, blurred_;
    glm::vec3 forward_{0.0f, 0.0f, -1.0f};
    // The temporal mean, its surface points and their normals, written and read in turn
    // (current_ is this frame's), and the camera they were seen from.
    gl::Handle mean_[2], points_[2], normals_[2];
    int current_ = 0;
    bool historyValid_ = false;
    glm::mat4 previousViewProjection_{1.0f};
};

}  // namespace voxgi
