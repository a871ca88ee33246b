#version 450 core
// ISR step 2 (seed 003 section 4.4): per coarse pixel, uPatches sender patches from a disc of
// uRadius coarse pixels around it (Vogel's spiral, turned per pixel and frame), each standing for
// pi uRadius^2 / uPatches pixels of the disc: the irradiance they send (rgb) and the fraction of
// the hemisphere their spheres hide (w; with uDiscs, their discs: a far field's weight), by
// shaders/shared/isr.h. No visibility between patches
// (the seed has none); gi/isr/isr_reference.cpp is the same gather on the CPU.
#include "common/screen_pass.glsl"
#include "shared/disc_samples.h"
#include "shared/isr.h"

uniform sampler2D uCoarsePosition;
uniform sampler2D uCoarseNormal;
uniform sampler2D uCoarseRadiance;
uniform int uPatches;
uniform float uRadius;  // coarse pixels
uniform int uFrame;
uniform bool uDiscs;

layout(rgba32f) writeonly uniform image2D uOutGather;

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    ivec2 size = textureSize(uCoarsePosition, 0);
    vec4 p = texelFetch(uCoarsePosition, pixel, 0);
    if (p.w <= 0.0) { imageStore(uOutGather, pixel, vec4(0.0)); return; }
    vec3 n = texelFetch(uCoarseNormal, pixel, 0).xyz;
    float rotation = discRotation(pixel, uFrame);
    vec4 sum = vec4(0.0);
    for (int i = 0; i < uPatches; ++i) {
        ivec2 q = pixel + ivec2(round(uRadius * vogelDisc(i, uPatches, rotation)));
        if (q == pixel || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        vec4 x = texelFetch(uCoarsePosition, q, 0);
        if (x.w <= 0.0) continue;
        vec4 radiance = texelFetch(uCoarseRadiance, q, 0);
        sum += isrPatchContribution(p.xyz, n, x.xyz, texelFetch(uCoarseNormal, q, 0).xyz, radiance.w, radiance.rgb, uDiscs);
    }
    imageStore(uOutGather, pixel, sum * (kPi * uRadius * uRadius / float(uPatches)));
}
