#version 450 core
// ISR step 4 (seed 003 section 4.5): the coarse irradiance brought to every pixel by the
// bilateral upsample (seed Eqs. 27-28: bilinear weights times depth agreement, here with normal
// agreement too), then the pixel's indirect radiance: diffuse albedo / pi times the irradiance,
// less the occluded fraction uAoStrength takes. Pixels whose four coarse samples all disagree
// take the one nearest in depth. A far field's light (gi/isr/isr_technique.h) is added where the
// patches leave the cosine-weighted hemisphere open: the rest of it is what they already send.
#define SCREEN_PASS_ADDITIVE
#include "common/screen_pass.glsl"
#include "common/gbuffer_textures.glsl"
#include "shared/isr.h"

uniform sampler2D uCoarseGather;  // rgb irradiance, w occlusion
uniform sampler2D uCoarseNormal;  // xyz normal, w depth
uniform int uFactor;
uniform vec3 uEye;
uniform vec3 uForward;
uniform float uAoStrength;
uniform sampler2D uFarLight;  // the far field's indirect radiance, when uHasFarLight
uniform bool uHasFarLight;

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    GBufferTexels t = fetchGBuffer(pixel);
    if (!gbufferHit(t.position)) return;
    GBufferSurface s = decodeGBuffer(t);
    float depth = dot(s.position - uEye, uForward);
    ivec2 size = textureSize(uCoarseGather, 0);
    vec2 g = (vec2(pixel) + 0.5) / float(uFactor) - 0.5;
    ivec2 base = ivec2(floor(g));
    vec2 f = g - vec2(base);
    vec4 sum = vec4(0.0);
    float weights = 0.0, nearestGap = 1e30;
    vec4 nearest = vec4(0.0);
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 q = clamp(base + o, ivec2(0), size - 1);
        vec4 c = texelFetch(uCoarseNormal, q, 0);
        if (c.w <= 0.0) continue;
        vec4 value = texelFetch(uCoarseGather, q, 0);
        vec2 b = mix(vec2(1.0) - f, f, vec2(o));
        float w = isrUpsampleWeight(b.x * b.y, depth, c.w, s.normal, c.xyz);
        sum += w * value;
        weights += w;
        if (abs(c.w - depth) < nearestGap) { nearestGap = abs(c.w - depth); nearest = value; }
    }
    vec4 e = weights > 1e-6 ? sum / weights : nearest;
    float occlusion = clamp(e.w, 0.0, 1.0);
    vec3 near = surfaceDiffuseAlbedo(s) * kInvPi * e.rgb * (1.0 - uAoStrength * occlusion);
    vec3 far = uHasFarLight ? (1.0 - occlusion) * texelFetch(uFarLight, pixel, 0).rgb : vec3(0.0);
    addToTarget(pixel, vec4(near + far, 1.0));
}
