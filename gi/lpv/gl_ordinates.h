// The ordinates' sweeps on the GPU (shaders/lpv/ordinates_sweep.comp, ordinates_reflect.comp,
// ordinates_resolve.comp): the transport of OrdinatesTransport::solve (gi/lpv/ordinates.h), with
// one dispatch per slab step for all bins, the surfaces and bins uploaded when they change
// (OrdinatesTransport::geometryRevision) and the sources (injected on the CPU) per solve. The
// irradiance cube is written straight into the brick pool the apply pass reads.
#pragma once

#include <cstddef>

#include <epoxy/gl.h>

#include "gi/lpv/ordinates.h"
#include "gl/resources.h"

namespace voxgi {

class GlOrdinates {
public:
    GlOrdinates();
    ~GlOrdinates();
    GlOrdinates(const GlOrdinates&) = delete;
    GlOrdinates& operator=(const GlOrdinates&) = delete;

    // Transports `sources` through `transport`'s surfaces (up to maxBounces sweeps, stopping like
    // the CPU once a sweep would carry under 1e-3 of the sources' power) and writes the cube into
    // the buffer `pool` from slot `firstSlot` on, one slot per brick of the transport (vec4
    // per light set: [face][slot][brick cell], shaders/shared/light_bricks.h). Returns the sweeps run.
    int solve(const OrdinatesTransport& transport, const OrdinatesTransport::Sources& sources, bool occlusion,
              int maxBounces, GLuint pool, std::size_t firstSlot);

private:
    struct Impl;
    Impl* impl_;
};

// Reads `slots` slots of a brick pool back from `firstSlot` on (for dumps and tests).
IrradianceBricks readBricks(GLuint pool, std::size_t firstSlot, std::size_t slots);

}  // namespace voxgi
