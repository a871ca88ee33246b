#version 450 core
// Test kernel: the shared display transform in GLSL (tests/test_display.cpp). values[i] =
// (linear rgb, exposure scale); results[i] = displaySrgb under curve uCurve.
#include "shared/tone_map.h"
layout(local_size_x = 64) in;
layout(std430, binding = 1) readonly buffer Values { vec4 values[]; };
layout(std430, binding = 2) writeonly buffer Results { vec4 results[]; };
uniform int uCount;
uniform int uCurve;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(uCount)) return;
    results[i] = vec4(displaySrgb(values[i].rgb, values[i].w, uCurve), 0.0);
}
