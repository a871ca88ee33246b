// A GI method as the frame renderer and the tools see it (Capsaicin's "render technique"): it
// updates its light each frame through the passes its plan lists, adds the indirect light it
// computed, draws the debug views its method declares, reports its stats, and dumps its volumes
// to .vdb. What a method is before it runs (settings, presets, plan, views) is gi/method.h.
#pragma once

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "gi/debug_view.h"
#include "gi/technique_plan.h"
#include "gi/technique_stat.h"
#include "gl/timers.h"
#include "scenes/scene.h"

namespace voxgi {

namespace gl {
class Program;
}

class SceneGpu;
class SkyVolumeTexture;

// The G-buffer of the current frame (textures owned by the frame renderer), encoded as
// shaders/shared/gbuffer.h says (encodeGBuffer / decodeGBuffer, for C++ and GLSL).
struct GBufferView {
    GLuint position = 0;  // RGBA32F: world position, w = 1 where a surface was hit
    GLuint normal = 0;    // RGBA16F: camera-facing shading normal, w = roughness
    GLuint albedo = 0;    // RGBA16F: albedo (texture applied), w = metallic
    GLuint emission = 0;  // RGBA32F: front-face emission, w = specular (F0 of the coat)
    int width = 0;
    int height = 0;
    glm::vec3 eye{0.0f};
    glm::mat4 viewProjection{1.0f};
    // The vertical field of view of the camera that drew these pixels: the scene camera's, wider
    // when the frame draws a guard band (TechniquePlan::guardBand); see pixelEdge.
    float fovYDegrees = 0.0f;
    // The picture's first pixel in these targets: the guard band's width and height in pixels
    // (0 without one). The picture is the middle (width - 2x) x (height - 2y).
    glm::ivec2 pictureOrigin{0};
    // For applyIndirect only: the direct layer summed over `directFrames` frames, this one
    // included (RGBA32F; radiance toward the camera, W/(m^2 sr), times directFrames).
    GLuint directSum = 0;
    int directFrames = 0;
    // 0: every pixel is seen from `eye`. Else an RGBA32F texture of each pixel's viewer (xyz):
    // surfaces seen through mirrors and glass (SecondaryLayerView).
    GLuint viewOrigin = 0;
    // The roughest GGX lobe whose reflection rays trace at these pixels (shading::tracedLobe:
    // < 0 none, 0 mirror-like lobes only; the hybrid method): the direct-light pass leaves those
    // lobes' reflection of quad lights (emitters the rays meet) to the rays, and the techniques'
    // glossy terms leave those lobes out.
    float tracedRoughness = -1.0f;
};

// Binds the G-buffer's four textures to units 0-3 under the names
// shaders/common/gbuffer_textures.glsl declares, and sets uTracedRoughness, for any deferred pass.
void bindGBufferTextures(const gl::Program& program, const GBufferView& g);

// Surfaces the camera sees through mirrors and glass (the hybrid method, gi/hybrid/): a G-buffer
// the frame lights with the same passes as its own, into the layer's light target.
struct SecondaryLayerView {
    GBufferView surfaces;
    GLuint lightFramebuffer = 0;  // cleared by the technique each frame; passes add into it
    glm::ivec4 scissor{0};        // x, y, width, height: the pixels that hold surfaces (passes draw only there)
};

// The camera's forward direction (unit, world space) from a perspective view-projection: the
// clip-space w row measures the distance along it.
inline glm::vec3 viewForward(const glm::mat4& viewProjection) {
    const glm::vec3 f(viewProjection[0][3], viewProjection[1][3], viewProjection[2][3]);
    const float length = glm::length(f);
    return length > 0.0f ? f / length : glm::vec3(0.0f);
}

// A pixel's edge on the image plane at unit distance from the eye, for the camera that drew `g`.
inline float pixelEdge(const GBufferView& g) {
    return 2.0f * std::tan(0.5f * glm::radians(g.fovYDegrees)) / float(g.height);
}

struct FrameInput {
    const Scene& scene;
    const SceneGpu& sceneGpu;  // the scene's GL buffers (draw() rasterizes every triangle)
    int frameIndex = 0;        // frames since init or the last resetAccumulation() (sampling patterns)
    gl::StageTimers& timers;   // bracket each pass: timers.begin(pass) ... end()
    const TechniquePlan& plan; // the passes to run (their names are the timer stages)
    // The sky-lighting volume when the frame plan has it (sky_volume), else null.
    const SkyVolumeTexture* sky = nullptr;
};

class GiTechnique {
public:
    virtual ~GiTechnique() = default;
    virtual std::string name() const = 0;
    // Computes this frame's light (inject, propagate, trace probes...). The G-buffer is ready.
    virtual void update(const FrameInput& input, const GBufferView& gbuffer) = 0;
    // Draws the indirect outgoing radiance (W/(m^2 sr)) of every G-buffer pixel into the bound
    // framebuffer; the renderer has set additive blending and the viewport.
    virtual void applyIndirect(const FrameInput& input, const GBufferView& gbuffer) = 0;
    // Writes the technique's volumes as OpenVDB grids.
    virtual void dumpVdb(const std::string& path) const;
    // One of the debug views its method declares (empty for a name it does not know).
    virtual DebugDrawing debugView(const std::string& view, const DebugViewContext& context) const;
    // Surfaces seen through mirrors and glass this frame, lit by the frame's passes after update;
    // then composite() adds what they bring to the pixels (the hybrid method). None by default.
    virtual std::vector<SecondaryLayerView> secondaryLayers() const { return {}; }
    virtual void composite(const FrameInput&, GLuint /*directFramebuffer*/, GLuint /*indirectFramebuffer*/) {}
    // The roughest lobe whose reflection the technique traces at the frame's pixels when the
    // plan runs hybrid.trace (GBufferView::tracedRoughness); none by default.
    virtual float tracedRoughness() const { return -1.0f; }
    // What its last update did, for benchmarks and the viewer.
    virtual std::vector<TechniqueStat> stats() const { return {}; }
    // Techniques whose light builds up over frames: after trackConvergence(), the relative change
    // of their light state over a window of recent updates, negative until the window has filled
    // (`voxgi eval` runs them until it falls below a threshold). None for techniques that start
    // over each frame.
    virtual void trackConvergence() {}
    virtual std::optional<double> lightStateChange() const { return std::nullopt; }
};

}  // namespace voxgi
