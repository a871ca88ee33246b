#version 450 core
// Probe update, one thread per interior texel of one probe tile (workgroup z = job). Defines:
// DISTANCE 0 (irradiance, cosine weights, stored as E^(1/gamma)) or 1 (moments, cos^exponent).
// The CPU reference is CpuBlend in gi/ddgi/probe_blend.cpp.
#include "common/octahedral.glsl"
#include "common/constants.glsl"
#include "ddgi/blend_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) readonly buffer Directions { vec4 directions[]; };  // blend rays
layout(std430, binding = 2) readonly buffer Rays { vec4 rayValues[]; };  // rgb radiance, a signed distance
layout(rgba32f, binding = 0) uniform image2D uAtlas;

uniform int uTexels;
uniform int uRays;
uniform float uExponent;
uniform float uGamma;
uniform float uIrradianceThreshold;
uniform float uBrightnessThreshold;
uniform float uBackfaceScale;

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= uTexels || texel.y >= uTexels) return;
    BlendJob job = jobs[gl_WorkGroupID.z];
    vec3 dir = octTexelDirection(texel, uTexels);
#if DISTANCE
    ivec2 at = ivec2(job.distanceX, job.distanceY) + 1 + texel;
#else
    ivec2 at = ivec2(job.irradianceX, job.irradianceY) + 1 + texel;
#endif
    vec4 previous = imageLoad(uAtlas, at);
    float hysteresis = job.hysteresis;
#if DISTANCE
    vec2 sum = vec2(0.0);
    float wsum = 0.0;
    for (int i = 0; i < uRays; ++i) {
        float c = max(0.0, dot(dir, directions[i].xyz));
        if (c <= 0.0) continue;
        float w = pow(c, uExponent);
        vec4 v = rayValues[job.rayBase + i];
        float d = v.w < 0.0 ? -uBackfaceScale * v.w : v.w;
        d = min(d, job.maxDistance);
        sum += w * vec2(d, d * d);
        wsum += w;
    }
    if (!(wsum > 0.0)) return;
    imageStore(uAtlas, at, vec4(mix(sum / wsum, previous.xy, hysteresis), 0.0, 0.0));
#else
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int i = 0; i < uRays; ++i) {
        vec4 v = rayValues[job.rayBase + i];
        if (v.w < 0.0) continue;
        float w = max(0.0, dot(dir, directions[i].xyz));
        sum += w * v.rgb;
        wsum += w;
    }
    if (!(wsum > 0.0)) return;
    vec3 e = max(PI * sum / wsum, vec3(0.0));
    vec3 encoded = pow(e, vec3(1.0 / uGamma));
    vec3 prev = previous.rgb;
    if (hysteresis > 0.0 && hysteresis < 1.0) {
        if (maxComponent(abs(prev - encoded)) > uIrradianceThreshold) hysteresis = max(0.0, hysteresis - 0.75);
        vec3 delta = encoded - prev;
        if (maxComponent(delta) > uBrightnessThreshold) encoded = prev + delta * 0.25;
    }
    imageStore(uAtlas, at, vec4(mix(encoded, prev, hysteresis), 1.0));
#endif
}
