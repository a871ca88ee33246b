#version 450 core
// ISR step 1 (seed 003 section 4.2): the G-buffer and the frame's direct light at coarse
// resolution, one patch per coarse pixel (uFactor^2 pixels). The patch's surface is the block's
// pixel nearest the eye; its radiance is the mean over the block's pixels on that surface (depth
// within 5 %, normals within 25 degrees), so a patch never mixes a wall with what is behind it,
// less their emission (the direct layer holds what emitters show the camera), plus the far
// field's indirect light where there is one (gi/isr/isr_technique.h).
#include "common/screen_pass.glsl"
#include "common/gbuffer_textures.glsl"
#include "shared/isr.h"

uniform sampler2D uDirectSum;   // the direct layer summed over uDirectFrames frames
uniform float uDirectFrames;
uniform sampler2D uFarLight;     // the far field's indirect radiance, when uHasFarLight
uniform bool uHasFarLight;
uniform int uFactor;
uniform vec3 uEye;
uniform vec3 uForward;
uniform float uPatchSolidAngle;  // a coarse pixel's solid angle on the camera's axis

layout(rgba32f) writeonly uniform image2D uOutPosition;   // xyz, w = 1 where a surface was hit
layout(rgba32f) writeonly uniform image2D uOutNormal;     // xyz, w = depth along the camera's axis (m)
layout(rgba32f) writeonly uniform image2D uOutRadiance;   // rgb radiance sent (W/(m^2 sr)), w = patch area (m^2)
layout(rgba32f) writeonly uniform image2D uOutAlbedo;     // rgb diffuse albedo

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    ivec2 base = pixel * uFactor;
    ivec2 size = textureSize(uPosition, 0);
    float nearest = 1e30;
    ivec2 chosen = ivec2(-1);
    for (int y = 0; y < uFactor; ++y)
        for (int x = 0; x < uFactor; ++x) {
            ivec2 q = min(base + ivec2(x, y), size - 1);
            vec4 p = texelFetch(uPosition, q, 0);
            if (!gbufferHit(p)) continue;
            float depth = dot(p.xyz - uEye, uForward);
            if (depth < nearest) { nearest = depth; chosen = q; }
        }
    if (chosen.x < 0) {
        imageStore(uOutPosition, pixel, vec4(0.0));
        imageStore(uOutNormal, pixel, vec4(0.0));
        imageStore(uOutRadiance, pixel, vec4(0.0));
        imageStore(uOutAlbedo, pixel, vec4(0.0));
        return;
    }
    GBufferSurface s = decodeGBuffer(fetchGBuffer(chosen));
    vec3 sum = vec3(0.0);
    float count = 0.0;
    for (int y = 0; y < uFactor; ++y)
        for (int x = 0; x < uFactor; ++x) {
            ivec2 q = min(base + ivec2(x, y), size - 1);
            vec4 p = texelFetch(uPosition, q, 0);
            if (!gbufferHit(p)) continue;
            float depth = dot(p.xyz - uEye, uForward);
            vec3 n = normalize(texelFetch(uNormal, q, 0).xyz);
            if (abs(depth - nearest) > 0.05 * nearest || dot(n, s.normal) < 0.9) continue;
            // What the surface reflects: its own emission is light the frame's emitters already
            // deliver as direct light, and sending it again would count it twice.
            sum += texelFetch(uDirectSum, q, 0).rgb / uDirectFrames - texelFetch(uEmission, q, 0).rgb;
            if (uHasFarLight) sum += texelFetch(uFarLight, q, 0).rgb;
            count += 1.0;
        }
    imageStore(uOutPosition, pixel, vec4(s.position, 1.0));
    imageStore(uOutNormal, pixel, vec4(s.normal, nearest));
    imageStore(uOutRadiance, pixel,
               vec4(max(sum / count, vec3(0.0)), isrPatchArea(s.position, s.normal, uEye, uForward, uPatchSolidAngle)));
    imageStore(uOutAlbedo, pixel, vec4(surfaceDiffuseAlbedo(s), 0.0));
}
