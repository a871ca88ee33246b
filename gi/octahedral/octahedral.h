// Octahedral mapping of the unit sphere onto a square (Cigolle et al. 2014), and the texel
// layout of octahedral probe tiles with a one-texel border. The same formulas are in
// shaders/common/octahedral.glsl; tests/test_ddgi_octahedral.cpp checks that the two agree.
#pragma once

#include <glm/glm.hpp>

namespace voxgi::oct {

// Unit direction -> point of the square [-1, 1]^2 (lower hemisphere folded over the corners).
glm::vec2 encode(glm::vec3 direction);
// Inverse of encode; any point of [-1, 1]^2 gives a unit direction.
glm::vec3 decode(glm::vec2 square);

// A tile holds `interior` x `interior` texels plus a one-texel border: (interior + 2)^2 texels.
inline int tileSize(int interior) { return interior + 2; }

// Direction at the centre of interior texel (x, y), 0 <= x, y < interior.
glm::vec3 texelDirection(int x, int y, int interior);

// Continuous texel coordinate inside a tile (texel centres at .5, border included) where a
// bilinear lookup of `direction` must sample. Always within [1, interior + 1].
glm::vec2 tileCoordinate(glm::vec3 direction, int interior);

// The interior texel a border texel copies so that bilinear filtering across the tile edge
// continues the sphere: edges mirror about their midpoint, corners take the opposite corner.
// (x, y) are tile coordinates in [0, interior + 1]; interior texels map to themselves.
glm::ivec2 borderSource(int x, int y, int interior);

}  // namespace voxgi::oct
