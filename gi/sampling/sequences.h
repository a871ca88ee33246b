// Low-discrepancy sequences shared by every sampler in voxgi (frame jitter, light samples,
// probe ray directions). Same formulas in shaders/common where GLSL needs them.
#pragma once

#include <glm/glm.hpp>

namespace voxgi {

// Roberts' R2 sequence: fract(offset + i * (1/g, 1/g^2)), g the plastic number. i = 0 gives
// `offset`, so the default first sample is the centre of the unit square.
glm::vec2 r2Sequence(int index, glm::vec2 offset = glm::vec2(0.5f));
// Its step (1/g, 1/g^2): r2Sequence(n + i, o) == fract(r2Sequence(n, o) + i * r2Step()).
glm::dvec2 r2Step();

// Radical inverse in base 2 (van der Corput), for Hammersley point sets.
float radicalInverse2(unsigned index);

// The i-th of n spherical Fibonacci directions (uniform over the sphere, unit length).
glm::vec3 sphericalFibonacci(int index, int count);

}  // namespace voxgi
