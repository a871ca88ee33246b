// The bridge that lets every header in shaders/shared/ compile as C++ (included as
// "shaders/shared/x.h") and as GLSL 4.50 (included as "shared/x.h" through gl/program.cpp).
// Each shared header includes this one and wraps its contents in
//     #ifdef __cplusplus
//     namespace voxgi::shading {
//     using namespace glm;
//     #endif
// so that C++ sees glm's vec3, dot, smoothstep... under their GLSL names. Shared code keeps to
// what both languages read the same way:
// - float literals with the f suffix (GLSL 4.50 accepts it; glm's vec * double does not compile);
// - functions marked `inline` (empty in GLSL), constants `constexpr` (`const` in GLSL);
// - results returned in structs (GLSL has no references, C++ no `out`), structs filled member by
//   member (GLSL constructors are not C++ aggregate initialization);
// - std430 structs of vec4 and ivec4 members, so both sides agree on the layout.
#ifndef VOXGI_SHARED_LANGUAGE_H
#define VOXGI_SHARED_LANGUAGE_H

#ifdef __cplusplus
#include <glm/glm.hpp>
#else
#define inline
#define constexpr const
#endif

#endif
