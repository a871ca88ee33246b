#version 450 core
// Probe update, one thread per interior texel of one probe tile (workgroup z = job). Defines:
// DISTANCE 0 (irradiance, cosine weights, stored as E^(1/gamma)) or 1 (moments,
// cos^DISTANCE_EXPONENT; the exponent is a constant of the program, so a whole one unrolls into
// its multiplies instead of looping over its bits for every ray and texel).
// The CPU reference is CpuBlend in gi/ddgi/probe_blend.cpp.
#include "common/octahedral.glsl"
#include "shared/constants.h"
#include "ddgi/blend_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) readonly buffer Directions { vec4 directions[]; };  // blend rays, unrotated
uniform mat3 uRayRotation;  // this frame's (gi/ddgi/probe_rays.h, RaySet::rotation)
layout(std430, binding = 2) readonly buffer Rays { vec4 rayValues[]; };  // rgb radiance, a signed distance
layout(rgba32f, binding = 0) uniform image2D uAtlas;

uniform int uTexels;
uniform int uRays;
uniform float uGamma;
uniform float uIrradianceThreshold;
uniform float uBrightnessThreshold;
uniform float uBackfaceScale;

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

// c^e by repeated squaring for whole exponents, as weightPow in gi/ddgi/probe_blend.cpp.
float weightPow(float c, float e) {
    if (e == floor(e) && e >= 1.0 && e <= 1024.0) {
        int k = int(e);
        float result = 1.0, base = c;
        while (k != 0) {
            if ((k & 1) != 0) result *= base;
            base *= base;
            k >>= 1;
        }
        return result;
    }
    return pow(c, e);
}

// Rays pass through shared memory in batches of 64, one load per thread (seed 004's update
// kernel), so each ray is read from the buffer once per workgroup instead of once per texel.
shared vec4 sDirection[64];
shared vec4 sValue[64];

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = texel.x < uTexels && texel.y < uTexels;
    BlendJob job = jobs[gl_WorkGroupID.z];
    vec3 dir = octTexelDirection(min(texel, ivec2(uTexels - 1)), uTexels);
#if DISTANCE
    ivec2 at = ivec2(job.distanceX, job.distanceY) + 1 + texel;
    vec2 sum = vec2(0.0);
#else
    ivec2 at = ivec2(job.irradianceX, job.irradianceY) + 1 + texel;
    vec3 sum = vec3(0.0);
#endif
    float wsum = 0.0;
    for (int batch = 0; batch < uRays; batch += 64) {
        int load = batch + int(gl_LocalInvocationIndex);
        if (load < uRays) {
            sDirection[gl_LocalInvocationIndex] = vec4(normalize(uRayRotation * directions[load].xyz), 0.0);
            sValue[gl_LocalInvocationIndex] = rayValues[job.rayBase + load];
        }
        barrier();
        int count = min(64, uRays - batch);
        for (int i = 0; i < count; ++i) {
            vec4 v = sValue[i];
#if DISTANCE
            float c = max(0.0, dot(dir, sDirection[i].xyz));
            if (c <= 0.0) continue;
            float w = weightPow(c, DISTANCE_EXPONENT);
            float d = v.w < 0.0 ? -uBackfaceScale * v.w : v.w;
            d = min(d, job.maxDistance);
            sum += w * vec2(d, d * d);
            wsum += w;
#else
            if (v.w < 0.0) continue;
            float w = max(0.0, dot(dir, sDirection[i].xyz));
            sum += w * v.rgb;
            wsum += w;
#endif
        }
        barrier();
    }
    if (!inside || !(wsum > 0.0)) return;
    vec4 previous = imageLoad(uAtlas, at);
    float hysteresis = job.hysteresis;
#if DISTANCE
    imageStore(uAtlas, at, vec4(mix(sum / wsum, previous.xy, hysteresis), 0.0, 0.0));
#else
    vec3 e = max(kPi * sum / wsum, vec3(0.0));
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
