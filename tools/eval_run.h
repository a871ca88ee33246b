// The measuring half of `voxgi eval`: renders a scene with one method and preset on the frame
// renderer (warm-up frames, then per-frame wall clock and per-stage GPU/CPU medians), and
// computes or reuses a cached path-traced reference.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gi/method.h"
#include "scenes/image.h"
#include "scenes/scene.h"

namespace voxgi::cli {

struct StageTiming {
    double gpuMs = 0.0;  // median over the timed frames (0 for CPU-only stages)
    double cpuMs = 0.0;
    std::size_t samples = 0;  // timed frames in which the stage ran
};

struct MethodRun {
    Image image;           // the mean of the frames after the warm-up
    double frameMs = 0.0;  // median wall clock of one frame (renderFrame, which waits for the GPU)
    int warmupFrames = 0;
    int timedFrames = 0;
    // Temporal techniques (GiTechnique::lightStateChange): the warm-up ran until the light state
    // changed less than RenderSettings::convergeBelow, or to the frame cap (converged false).
    bool temporal = false, converged = false;
    double convergeMs = 0.0;  // wall clock of the warm-up frames, summed
    std::vector<std::pair<std::string, StageTiming>> stages;  // in the renderer's order
    // The technique's stats (GiTechnique::stats), medians over the timed frames; times get
    // "_ms" appended to their name.
    std::vector<std::pair<std::string, double>> stats;
};

struct RenderSettings {
    int width = 0, height = 0;  // the scene camera's size already overridden
    int frames = 0;             // frames accumulated into the image, warm-up included
    int warmup = 0;             // first frames left out of the timing and of the image
    // Temporal techniques warm up until their light state changes less than this over their
    // window (at least `warmup` frames), or for maxWarmup frames.
    double convergeBelow = 0.002;
    int maxWarmup = 300;
};

// Needs a current GL context. The preset's and then the `extra` gi settings are applied over the
// scene's.
MethodRun renderMethod(const Scene& scene, const std::string& method, const Preset& preset,
                       const RenderSettings& settings, const SettingList& extra = {});

// One method and preset on one frame renderer whose camera moves from view to view, as a user's
// camera does: light that builds up over frames (DDGI) settles once, at the first view, and every
// later view starts from that light state (`voxgi eval --views`). Needs a current GL context.
class MethodSession {
public:
    MethodSession(const Scene& scene, const std::string& method, const Preset& preset, const RenderSettings& settings,
                  const SettingList& extra = {});
    ~MethodSession();
    MethodSession(const MethodSession&) = delete;
    MethodSession& operator=(const MethodSession&) = delete;
    // The warm-up (for a temporal technique: until its light settles again) and timed frames at
    // `camera` (its size must be the session's).
    MethodRun render(const Camera& camera);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

struct Reference {
    Image image;
    int spp = 0;
    double seconds = 0.0;  // path tracing time when computed (from the cache's record otherwise)
    bool fromCache = false;
    std::string path;
};

// `cacheDir`/<name>-<w>x<h>-<spp>spp-<hash>.exr (+ .json with spp and time) when present, else
// path traced and written there. `caustics` false: PathTracerOptions::caustics (the file name
// says "nocaustics").
Reference loadOrRenderReference(const Scene& scene, const std::string& name, int spp, const std::string& cacheDir,
                                bool caustics = true);
// A reference given as a file; its size must match the scene camera's.
Reference readReference(const std::string& path, const Scene& scene);

}  // namespace voxgi::cli
