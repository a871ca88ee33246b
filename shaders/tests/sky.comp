#version 450 core
// Test kernel: the sky's radiance through shaders/common/sky.glsl, for comparison with the C++
// lookup (tests/test_sky.cpp). results[i] = radiance toward directions[i].
#include "common/sky.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 1) readonly buffer Directions { vec4 directions[]; };
layout(std430, binding = 2) writeonly buffer Results { vec4 results[]; };
uniform int uCount;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(uCount)) return;
    results[i] = vec4(skyRadiance(directions[i].xyz), 0.0);
}
