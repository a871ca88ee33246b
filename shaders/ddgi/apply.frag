#version 450 core
// Indirect outgoing radiance of every G-buffer pixel from the DDGI field:
// (1 - metallic)(1 - specular) albedo / pi * E_indirect.
#include "shared/constants.h"
#include "ddgi/sampling.glsl"

uniform sampler2D uPosition;
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler2D uEmission;
uniform vec3 uEye;

layout(location = 0) out vec4 outColor;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 pos = texelFetch(uPosition, pixel, 0);
    if (pos.w == 0.0) { outColor = vec4(0.0); return; }
    vec3 n = normalize(texelFetch(uNormal, pixel, 0).xyz);
    vec4 am = texelFetch(uAlbedo, pixel, 0);
    float specular = texelFetch(uEmission, pixel, 0).w;
    vec3 toViewer = uEye - pos.xyz;
    float len = length(toViewer);
    toViewer = len > 0.0 ? toViewer / len : n;
    vec3 e = ddgiSampleIrradiance(pos.xyz, n, toViewer);
    outColor = vec4((1.0 - am.w) * (1.0 - specular) * am.rgb * kInvPi * e, 1.0);
}
