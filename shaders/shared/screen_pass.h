// The side of a per-pixel compute pass's square workgroup, for gl/screen_pass.cpp's dispatch and
// shaders/common/screen_pass.glsl's local size.
#ifndef VOXGI_SHARED_SCREEN_PASS_H
#define VOXGI_SHARED_SCREEN_PASS_H

#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

constexpr int kScreenPassGroupSide = 8;

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
