// Cascaded shadow maps for a directional light (the sun): the camera's view split by distance
// into slices, each covered by its own orthographic map, finest first. Stabilised so that
// shadows do not shimmer as the camera moves: each slice is covered by the bounding sphere of
// its frustum piece (whose size depends on the camera's lens only, not on where it looks), and
// each map's origin is snapped to whole texels of a grid fixed in light space.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace voxgi {

struct SunCascade {
    glm::mat4 worldToMap{1.0f};  // world -> map: xy in [0, 1] across the map, z its depth in [0, 1]
    float texelWorld = 0.0f;     // the world size of one texel (m)
    float splitFar = 0.0f;       // the slice's far end, as distance along the camera's axis (m)
};

struct SunCascades {
    std::vector<SunCascade> cascades;  // finest (nearest the camera) first
    glm::mat3 worldToLight{1.0f};      // rotation into light space: x, y across the maps, z the way light travels
    float depthRange = 0.0f;           // world length (m) of map depth 0..1, the same in every cascade
};

// How the view is split: the weight of the logarithmic split scheme against the uniform one
// (0.8 gives the near slices most of the resolution but keeps the far ones usable).
constexpr float kCascadeLogWeight = 0.8f;

// Cascades of `mapSize`-texel square maps for light travelling along unit `direction`, over what
// `camera` sees of the scene `bounds` (depth: every point of `bounds`, so casters outside the
// view still shadow it). The last slice ends where the camera can see no more of `bounds`,
// rounded up to a power of 2^(1/4) so that it changes in steps as the camera moves.
SunCascades fitSunCascades(const Camera& camera, glm::vec3 direction, const Bounds& bounds, int mapSize, int count);

}  // namespace voxgi
