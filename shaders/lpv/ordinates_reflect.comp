#version 450 core
// After a sweep (gi/lpv/ordinates.cpp, reflectionSources): each surface's reflections, summed
// over the three axis groups, become the next sweep's sources, by its one-plane shares or by
// its axis faces' hemispheres; the reflection buffers are cleared for the next sweep, and each
// workgroup writes the power it turned into sources (the CPU sums them to decide when to stop).
layout(local_size_x = 64) in;

layout(std430, binding = 3) writeonly buffer Sources { float sources[]; };  // [bin][surface][rgb]
layout(std430, binding = 7) buffer Reflected { vec4 reflected[]; };         // [axis][surface][face]
layout(std430, binding = 8) readonly buffer PlaneShares { float planeShares[]; };  // [surface][bin]
layout(std430, binding = 9) readonly buffer FaceShares { float faceShares[]; };    // [face][bin]
layout(std430, binding = 10) writeonly buffer Power { float power[]; };             // per workgroup

uniform int uSurfaces;
uniform int uBins;
uniform int uClear;  // 1: clear the reflections after reading them

shared float partial[64];

void main() {
    int s = int(gl_GlobalInvocationID.x);
    float watts = 0.0;
    if (s < uSurfaces) {
        vec3 r[6];
        vec3 total = vec3(0.0);
        for (int f = 0; f < 6; ++f) {
            r[f] = vec3(0.0);
            for (int g = 0; g < 3; ++g) {
                int i = (g * uSurfaces + s) * 6 + f;
                r[f] += reflected[i].rgb;
                if (uClear != 0) reflected[i] = vec4(0.0);
            }
            total += r[f];
            watts += r[f].r + r[f].g + r[f].b;
        }
        bool plane = planeShares[s * uBins] >= 0.0;
        for (int k = 0; k < uBins; ++k) {
            vec3 p = vec3(0.0);
            if (plane) {
                p = total * planeShares[s * uBins + k];
            } else {
                for (int f = 0; f < 6; ++f) p += r[f] * faceShares[f * uBins + k];
            }
            int o = (k * uSurfaces + s) * 3;
            sources[o] = p.r;
            sources[o + 1] = p.g;
            sources[o + 2] = p.b;
        }
    }
    partial[gl_LocalInvocationID.x] = watts;
    barrier();
    for (uint half_ = 32u; half_ > 0u; half_ >>= 1) {
        if (gl_LocalInvocationID.x < half_) partial[gl_LocalInvocationID.x] += partial[gl_LocalInvocationID.x + half_];
        barrier();
    }
    if (gl_LocalInvocationID.x == 0u) power[gl_WorkGroupID.x] = partial[0];
}
