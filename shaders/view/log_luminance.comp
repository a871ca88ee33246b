#version 450 core
// The viewer's auto exposure: the sum of log luminance over the lit pixels of a 64 x 64 grid of
// the shown layer (beauty, direct or indirect), and how many there were (shaders/shared/
// tone_map.h; scenes/image.cpp autoExposureStops does the same over every pixel).
#include "shared/tone_map.h"
layout(local_size_x = 256) in;
layout(binding = 0) uniform sampler2D uDirect;    // sums over the accumulated frames
layout(binding = 1) uniform sampler2D uIndirect;
layout(std430, binding = 0) writeonly buffer Result { vec2 result; };  // (sum of log L, lit samples)
uniform float uInvFrames;
uniform int uMode;  // DisplayMode: 0 beauty, 1 direct, 2 indirect
shared vec2 partial[256];
void main() {
    ivec2 size = textureSize(uDirect, 0);
    vec2 sum = vec2(0.0);
    for (uint i = gl_LocalInvocationIndex; i < 4096u; i += 256u) {
        ivec2 p = ivec2((ivec2(int(i % 64u), int(i / 64u)) * 2 + 1) * size / 128);
        vec3 direct = texelFetch(uDirect, p, 0).rgb, indirect = texelFetch(uIndirect, p, 0).rgb;
        vec3 c = (uMode == 1 ? direct : uMode == 2 ? indirect : direct + indirect) * uInvFrames;
        float l = luminanceRec709(c);
        if (l > 0.0 && !isinf(l)) sum += vec2(log(l), 1.0);
    }
    partial[gl_LocalInvocationIndex] = sum;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1) {
        if (gl_LocalInvocationIndex < stride) partial[gl_LocalInvocationIndex] += partial[gl_LocalInvocationIndex + stride];
        barrier();
    }
    if (gl_LocalInvocationIndex == 0u) result = partial[0];
}
