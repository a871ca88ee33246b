// Light and blocker injection on the GPU (GL back end): the RSM texels and G-buffer samples
// go straight from their textures into each cascade's 3D textures, with the same formulas as
// gi/lpv/injection.h (cell placement, normal and light offsets, flux and area scaling).
//
// Every texel is drawn as one point into a layered framebuffer over the 3D textures (the vertex
// shader fetches the texel and computes its cell, the geometry shader picks the layer) with
// additive RGBA32F blending. GL blends in primitive order, and the points are drawn in texel
// order, so each cell sums its surfels in the same order as the CPU loop. Blockers of one source
// are summed (albedo by GL_MAX blending) into a scratch volume, which a compute pass merges into
// the geometry volume with mergeBlockers' rule (max within a facing, sum across opposite ones).
#pragma once

#include <memory>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "gi/lpv/cascades.h"
#include "gi/lpv/injection.h"
#include "gi/lpv/light_volume.h"
#include "gi/lpv/rsm.h"
#include "gi/technique.h"
#include "gl/resources.h"

namespace voxgi {

// The GL volumes of one cascade the injection writes (GlPropagator's injected and geometry).
struct GlCascadeTargets {
    CascadeGrid grid;
    GLuint light[3] = {0, 0, 0};  // r, g, b: RGBA32F N^3
    GLuint blocker = 0;           // RGBA32F (N + 1)^3 corner samples
    GLuint albedo = 0;            // RGBA32F (N + 1)^3, rgb
};

// Which G-buffer pixels become blocker surfels (both back ends sample the same ones): every
// `stride`-th pixel from stride / 2 in both axes, the larger side reduced to at most `target`.
struct GBufferSampling {
    int stride = 1;
    int columns = 0, rows = 0;  // samples per row and per column
    float pixel = 0.0f;         // a pixel's edge on the unit-distance image plane
    glm::vec3 forward{0.0f, 0.0f, -1.0f};

    static GBufferSampling of(const GBufferView& g, int target);
    int count() const { return columns * rows; }
};

// A CPU-made geometry volume (the voxelized static blockers) kept on the GPU.
class GlBlockerVolume {
public:
    explicit GlBlockerVolume(int resolution);
    void upload(const BlockerVolume& volume);
    GLuint blocker() const { return blocker_.id(); }
    GLuint albedo() const { return albedo_.id(); }

private:
    int corners_;
    gl::Handle blocker_, albedo_;
};

class GlInjector {
public:
    explicit GlInjector(int resolution);
    ~GlInjector();
    GlInjector(const GlInjector&) = delete;
    GlInjector& operator=(const GlInjector&) = delete;

    void clearLight(const GlCascadeTargets& t);
    void clearGeometry(const GlCascadeTargets& t);
    // injectLight(): the face's lit texels as VPLs; with cascades, the VPLs' shares of cascade
    // `level`'s ring (inner = false) or inner volume (gi/lpv/cascades.h) go to t's light.
    void injectLight(const RsmFace& face, const InjectionOffsets& offsets, const GlCascadeTargets& t);
    void injectLight(const RsmFace& face, const InjectionOffsets& offsets, const GlCascadeTargets& t,
                     const std::vector<CascadePlacement>& cascades, std::size_t level, bool inner);
    // injectBlockers(): one source's blockers summed, then merged into the geometry volume.
    void injectBlockers(const RsmFace& face, const GlCascadeTargets& t);
    void injectBlockers(const GBufferView& g, const GBufferSampling& sampling, const GlCascadeTargets& t);
    // BlockerVolume::mergeMax() with a volume already on the GPU.
    void mergeBlockers(const GlBlockerVolume& source, const GlCascadeTargets& t);

private:
    void drawVpls(const RsmFace& face, const InjectionOffsets& offsets, const GlCascadeTargets& t);
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace voxgi
