// Luminance of linear Rec. 709 / sRGB radiance, for C++ (light and lobe selection, sky
// sampling, auto exposure) and GLSL (the display transform).
#ifndef VOXGI_SHARED_COLOR_H
#define VOXGI_SHARED_COLOR_H

#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

inline float luminanceRec709(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
