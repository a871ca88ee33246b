// LPV propagation with GL compute (shaders/lpv/propagate.comp): the GPU twin of
// CpuPropagator, dense over the cascade. Results stay in 3D textures for the apply pass.
// The injected light and the geometry volume are GL textures too: GlInjector writes them on
// the GPU (no CPU round trip), or propagate() uploads CPU-injected volumes into them.
#pragma once

#include <memory>

#include <epoxy/gl.h>

#include "gi/lpv/light_volume.h"
#include "gi/lpv/propagation.h"

namespace voxgi {

// It propagates `lightSets` independent light volumes through the same geometry (a cascade's
// ring and inner light, gi/lpv/cascades.h); `set` picks one.
class GlPropagator {
public:
    explicit GlPropagator(int resolution, int lightSets = 1);
    ~GlPropagator();
    GlPropagator(const GlPropagator&) = delete;
    GlPropagator& operator=(const GlPropagator&) = delete;

    int resolution() const;
    int lightSets() const;

    // Uploads the injected light (of set 0) and the geometry, runs `steps` iterations on the GPU.
    void propagate(const LightVolume& injected, const BlockerVolume& geometry, int steps,
                   const PropagationOptions& options);
    // Runs `steps` iterations of every set from what the injected-light and geometry textures
    // hold now.
    void propagateInjected(int steps, const PropagationOptions& options);

    // The injected light (r, g, b RGBA32F N^3) and the geometry volume (blocker SH and albedo,
    // RGBA32F (N + 1)^3 corner samples), read by propagateInjected().
    GLuint injected(int channel, int set = 0) const;
    GLuint blocker() const;
    GLuint albedo() const;

    // The accumulated light (r, g, b RGBA32F 3D textures).
    GLuint accumulated(int channel, int set = 0) const;
    // Reads the accumulated light back (for parity tests and dumps); the grid is left as is.
    void readBack(LightVolume& out, int set = 0) const;
    void readBackInjected(LightVolume& out, int set = 0) const;
    void readBackGeometry(BlockerVolume& out) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace voxgi
