// LPV propagation with GL compute (shaders/lpv/propagate.comp): the GPU twin of
// CpuPropagator, dense over the cascade. Results stay in 3D textures for the apply pass.
#pragma once

#include <memory>

#include <epoxy/gl.h>

#include "gi/lpv/light_volume.h"
#include "gi/lpv/propagation.h"

namespace voxgi {

class GlPropagator {
public:
    explicit GlPropagator(int resolution);
    ~GlPropagator();
    GlPropagator(const GlPropagator&) = delete;
    GlPropagator& operator=(const GlPropagator&) = delete;

    // Uploads the injected light and the geometry, runs `steps` iterations on the GPU.
    void propagate(const LightVolume& injected, const BlockerVolume& geometry, int steps,
                   const PropagationOptions& options);
    // The accumulated light (r, g, b RGBA32F 3D textures).
    GLuint accumulated(int channel) const;
    // Reads the accumulated light back (for parity tests and dumps).
    void readBack(LightVolume& out) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace voxgi
