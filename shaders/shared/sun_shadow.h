// The sun's cascaded shadow maps as C++ (render/frame/sun_cascades.h, the frame renderer) and
// GLSL (shaders/frame/sun_shadow.glsl) both see them.
#ifndef VOXGI_SHARED_SUN_SHADOW_H
#define VOXGI_SHARED_SUN_SHADOW_H

#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
#endif

// Cascades over the picture per directional light at most, and the maps in all: one more covers
// a guard band's surfaces beyond the picture (render/frame/frame_renderer.cpp), so that the
// picture's own cascades, and its shadows, are the same with a band as without.
constexpr int kMaxSunCascades = 4;
constexpr int kMaxSunMaps = kMaxSunCascades + 1;
// The side (texels) of the tiles whose nearest depth bounds the blocker search, and the widest
// soft-shadow kernel's radius: a kernel around any texel stays within its tile's 3 x 3
// neighbours. Cascade maps are a whole number of tiles.
constexpr int kSunTileTexels = 32;

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
