// The rasterized frame: G-buffer, shadow maps, physically based direct light for every light
// kind, HDR accumulation over frames (pixel jitter and area-light samples), read back as an
// Image with AOVs. GI techniques add their indirect light on top of this.
#pragma once

#include <memory>

#include "gi/technique.h"
#include "gl/timers.h"
#include "render/frame/frame_plan.h"
#include "scenes/image.h"
#include "scenes/scene.h"

namespace voxgi {

struct FrameOptions {
    int width = 0;    // 0 = the scene camera's resolution
    int height = 0;
    int shadowMapSize = 2048;     // spot maps
    int sunMapSize = 2048;        // each cascade of a directional light (render/frame/sun_cascades.h)
    int sunCascades = 4;          // 1..shading::kMaxSunCascades over the picture (one more over a guard band)
    // Keep the sun's maps while the camera and the sun stand still (frames that accumulate);
    // false draws them every frame, what a moving camera costs (eval times frames so).
    bool keepSunMaps = true;
    int cubeShadowSize = 512;     // point lights and quad-light samples, per face
    bool jitter = true;           // sub-pixel jitter from the second frame on (antialiasing)
    // Draw the guard band a method's plan asks for (TechniquePlan::guardBand). The viewer turns
    // it off: its display and debug drawings read the frame's textures whole.
    bool guardBand = true;
};

class FrameRenderer {
public:
    // Needs a current GL 4.5 context. Throws gl::GlError on shader or framebuffer failure, and
    // InputError / NotImplementedError for a bad method or setting. Runs exactly the passes
    // of `plan` (planFrame), with the technique of plan.method.
    FrameRenderer(const Scene& scene, const FrameOptions& options, FramePlan plan);
    // The plan of `method` for one frame.
    FrameRenderer(const Scene& scene, const FrameOptions& options, const std::string& method = "direct");
    ~FrameRenderer();
    FrameRenderer(const FrameRenderer&) = delete;
    FrameRenderer& operator=(const FrameRenderer&) = delete;

    // Renders one frame (one sample of every light) and adds it to the accumulation.
    void renderFrame();
    int framesAccumulated() const;
    // The picture's size; textures() are larger by the guard band when one is drawn.
    int width() const;
    int height() const;

    // The average so far: layers beauty, direct, indirect (zero without GI), albedo, normal, depth.
    Image resolve();
    gl::StageTimers& timers();
    GiTechnique* technique();
    const FramePlan& plan() const;

    // For the interactive viewer: restart the average (the camera or a light moved; the
    // technique keeps its state), switch the GI method (plans again and restarts; on an error
    // the old method stays), and the textures behind resolve(): direct and indirect are sums
    // over framesAccumulated().
    void resetAccumulation();
    void setMethod(const std::string& method);
    struct Textures {
        GLuint direct = 0, indirect = 0, albedo = 0, normal = 0, position = 0;
        int width = 0, height = 0;     // the targets' size: the picture's and a guard band's
        glm::ivec2 pictureOrigin{0};   // the picture's first pixel in them (GBufferView's)
    };
    Textures textures() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// How many frames a scene needs by default: area lights are sampled once per frame.
int defaultFrameCount(const Scene& scene);

}  // namespace voxgi
