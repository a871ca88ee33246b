// The ordinates' sweeps on the GPU (shaders/lpv/ordinates_sweep.comp, ordinates_reflect.comp,
// ordinates_resolve.comp): the transport of OrdinatesTransport::solve (gi/lpv/ordinates.h), with
// one dispatch per slab step for all bins, the surfaces and bins uploaded when they change
// (OrdinatesTransport::geometryRevision) and the sources (injected on the CPU) per solve. The irradiance cube is written straight into the
// texture the apply pass reads.
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
    // `cube` (N x N x 6N RGBA32F). Returns the sweeps run.
    int solve(const OrdinatesTransport& transport, const OrdinatesTransport::Sources& sources, bool occlusion,
              int maxBounces, GLuint cube);

private:
    struct Impl;
    Impl* impl_;
};

// Reads a cube texture back into the faces' arrays (for dumps and tests).
std::array<std::vector<glm::vec4>, kOrdinateFaces> readCube(GLuint cube, int resolution);

}  // namespace voxgi
