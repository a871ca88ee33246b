// Irradiance from the probe field at a shading point: the 8-probe cage of each volume,
// weighted trilinear x wrap (backface) x Chebyshev visibility x weight crushing, with normal
// and view bias; cascades blend finest first. The CPU reference of shaders/ddgi/sampling.glsl.
#pragma once

#include <glm/glm.hpp>

#include "gi/ddgi/probe_field.h"

namespace voxgi {

// Chebyshev's upper bound on the chance that a point at distance r from the probe is visible,
// from the distance moments (mean, mean of squares): 1 for r <= mean, 0 when the variance is
// zero and r > mean.
float chebyshevVisibility(float r, float mean, float meanSquare);

// 0 outside, 1 more than one cell inside the volume, linear across the outermost cell.
float volumeBlendWeight(const ProbeVolume& volume, glm::vec3 p);

// Irradiance (W/m^2) at p for unit normal n, seen from unit direction `toViewer`. Zero where
// no probe contributes (every cage probe off).
glm::vec3 sampleIrradiance(const ProbeField& field, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer);
// One volume only; `weightSum` receives the sum of its probe weights.
glm::vec3 sampleVolumeIrradiance(const ProbeField& field, int volume, glm::vec3 p, glm::vec3 n, glm::vec3 toViewer,
                                 float* weightSum = nullptr);

// Occlusion probes (seed 004 ch. 5): visibility of up to four lights (one per channel) at the
// surface point p, reconstructed from the occlusion atlas with the same cage weights, looked up
// in the direction from each probe to p. All ones without an occlusion atlas.
glm::vec4 sampleOcclusion(const ProbeField& field, glm::vec3 p, glm::vec3 n);

}  // namespace voxgi
