// The one pi of voxgi, for C++ and GLSL.
#ifndef VOXGI_SHARED_CONSTANTS_H
#define VOXGI_SHARED_CONSTANTS_H

#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;

#ifdef __cplusplus
// Image metrics (gi/metrics/) compute in double precision.
constexpr double kPiDouble = 3.14159265358979323846;
}  // namespace voxgi::shading
#endif

#endif
