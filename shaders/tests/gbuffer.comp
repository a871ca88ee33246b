#version 450 core
// Test kernel: the shared G-buffer encoding and diffuse albedo in GLSL, for comparison with
// their C++ compilation (tests/test_light_model.cpp). Surface i comes in as four vec4s
// (position, roughness), (normal, metallic), (albedo, specular), (emission, transmission); out go its
// four encoded texels, the decoded surface in the same four-vec4 form, and
// (diffuseAlbedo, hit), (gbufferDiffuseAlbedo of the texels, 0).
#include "shared/gbuffer.h"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Surfaces { vec4 surfaces[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform int uCount;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(uCount)) return;
    GBufferSurface s;
    s.position = surfaces[4u * i].xyz;
    s.roughness = surfaces[4u * i].w;
    s.normal = surfaces[4u * i + 1u].xyz;
    s.metallic = surfaces[4u * i + 1u].w;
    s.albedo = surfaces[4u * i + 2u].xyz;
    s.specular = surfaces[4u * i + 2u].w;
    s.emission = surfaces[4u * i + 3u].xyz;
    s.transmission = surfaces[4u * i + 3u].w;
    GBufferTexels t = encodeGBuffer(s);
    GBufferSurface d = decodeGBuffer(t);
    uint o = 10u * i;
    results[o] = t.position;
    results[o + 1u] = t.normal;
    results[o + 2u] = t.albedo;
    results[o + 3u] = t.emission;
    results[o + 4u] = vec4(d.position, d.roughness);
    results[o + 5u] = vec4(d.normal, d.metallic);
    results[o + 6u] = vec4(d.albedo, d.specular);
    results[o + 7u] = vec4(d.emission, d.transmission);
    results[o + 8u] = vec4(diffuseAlbedo(s.albedo, s.metallic, s.specular, s.transmission), gbufferHit(t.position) ? 1.0f : 0.0f);
    results[o + 9u] = vec4(gbufferDiffuseAlbedo(t.position, t.albedo, t.emission), 0.0f);
}
