#version 450 core
// Indirect outgoing radiance of every G-buffer pixel from the DDGI field:
// diffuse albedo / pi * E_indirect.
#include "shared/constants.h"
#include "common/gbuffer_textures.glsl"
#include "ddgi/sampling.glsl"

uniform vec3 uEye;

layout(location = 0) out vec4 outColor;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    GBufferTexels t = fetchGBuffer(pixel);
    if (!gbufferHit(t.position)) { outColor = vec4(0.0); return; }
    GBufferSurface s = decodeGBuffer(t);
    vec3 toViewer = uEye - s.position;
    float len = length(toViewer);
    toViewer = len > 0.0 ? toViewer / len : s.normal;
    vec3 e = ddgiSampleIrradiance(s.position, s.normal, toViewer);
    outColor = vec4(surfaceDiffuseAlbedo(s) * kInvPi * e, 1.0);
}
