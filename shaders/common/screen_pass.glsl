// Per-pixel passes as compute shaders (gl/screen_pass.h says why): one invocation per pixel of
// uScreenRect, in square groups (shared/screen_pass.h). A pass calls screenPixel() first and
// returns when it is false; an additive pass then hands its value to addToTarget(), as a draw
// with GL_ONE, GL_ONE blending would add it.
#ifndef VOXGI_SCREEN_PASS_GLSL
#define VOXGI_SCREEN_PASS_GLSL

#include "shared/screen_pass.h"

layout(local_size_x = kScreenPassGroupSide, local_size_y = kScreenPassGroupSide) in;

uniform ivec4 uScreenRect;  // x, y, width, height

// The pixel this invocation shades; false for the spare invocations of the last groups.
bool screenPixel(out ivec2 pixel) {
    ivec2 local = ivec2(gl_GlobalInvocationID.xy);
    pixel = uScreenRect.xy + local;
    return all(lessThan(local, uScreenRect.zw));
}

#ifdef SCREEN_PASS_ADDITIVE
// The target that gl::addToBoundTarget binds: each pixel is read and written by its own
// invocation only.
layout(rgba32f) uniform image2D uAdditiveTarget;

void addToTarget(ivec2 pixel, vec4 value) { imageStore(uAdditiveTarget, pixel, imageLoad(uAdditiveTarget, pixel) + value); }
#endif
#endif
