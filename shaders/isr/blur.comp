#version 450 core
// ISR step 3: one direction of a separable Gaussian over the coarse gather (sigma = radius / 2),
// weighted by depth and normal agreement so that it does not carry light across silhouettes
// (the seed's plain Gaussian left halos there).
#include "common/screen_pass.glsl"
#include "shared/isr.h"

uniform sampler2D uSource;
uniform sampler2D uCoarseNormal;  // xyz normal, w depth
uniform ivec2 uStep;              // (1, 0) or (0, 1)
uniform int uRadius;

layout(rgba32f) writeonly uniform image2D uOutBlurred;

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    ivec2 size = textureSize(uSource, 0);
    vec4 centre = texelFetch(uCoarseNormal, pixel, 0);
    if (centre.w <= 0.0) { imageStore(uOutBlurred, pixel, vec4(0.0)); return; }
    float sigma = max(0.5 * float(uRadius), 0.5);
    vec4 sum = vec4(0.0);
    float weights = 0.0;
    for (int k = -uRadius; k <= uRadius; ++k) {
        ivec2 q = clamp(pixel + k * uStep, ivec2(0), size - 1);
        vec4 other = texelFetch(uCoarseNormal, q, 0);
        if (other.w <= 0.0) continue;
        float w = exp(-0.5 * float(k * k) / (sigma * sigma)) *
                  isrUpsampleWeight(1.0, centre.w, other.w, centre.xyz, other.xyz);
        sum += w * texelFetch(uSource, q, 0);
        weights += w;
    }
    imageStore(uOutBlurred, pixel, weights > 0.0 ? sum / weights : vec4(0.0));
}
