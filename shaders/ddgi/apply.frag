#version 450 core
// Indirect outgoing radiance of every G-buffer pixel from the DDGI field:
// diffuse albedo / pi * E_indirect.
#include "shared/constants.h"
#include "shared/gbuffer.h"
#include "ddgi/sampling.glsl"

uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler2D uEmission;
uniform vec3 uEye;

layout(location = 0) out vec4 outColor;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    GBufferTexels t;
    t.position = texelFetch(uPosition, pixel, 0);
    if (!gbufferHit(t.position)) { outColor = vec4(0.0); return; }
    t.normal = texelFetch(uNormal, pixel, 0);
    t.albedo = texelFetch(uAlbedo, pixel, 0);
    t.emission = texelFetch(uEmission, pixel, 0);
    GBufferSurface s = decodeGBuffer(t);
    vec3 toViewer = uEye - s.position;
    float len = length(toViewer);
    toViewer = len > 0.0 ? toViewer / len : s.normal;
    vec3 e = ddgiSampleIrradiance(s.position, s.normal, toViewer);
    outColor = vec4(diffuseAlbedo(s.albedo, s.metallic, s.specular) * kInvPi * e, 1.0);
}
