#version 450 core
// Test kernel: for each direction, the SH basis, the cosine lobe and the convolution of a
// fixed function, written out for comparison with gi/sh/sh.h.
#include "common/sh.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Dirs { vec4 dirs[]; };
layout(std430, binding = 1) writeonly buffer Out { vec4 values[]; };
void main() {
    uint i = gl_GlobalInvocationID.x;
    vec3 w = dirs[i].xyz;
    values[3u * i] = shBasis(w);
    values[3u * i + 1u] = shCosineLobe(w);
    vec4 f = vec4(0.7, -0.2, 0.4, 0.1);
    values[3u * i + 2u] = vec4(shEvaluate(f, w), shConvolveCosine(f, w), 0.0, 0.0);
}
