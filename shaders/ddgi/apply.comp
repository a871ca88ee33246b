#version 450 core
// Indirect outgoing radiance of every G-buffer pixel from the DDGI field:
// diffuse albedo / pi * E_indirect.
#define SCREEN_PASS_ADDITIVE
#include "common/screen_pass.glsl"
#include "shared/constants.h"
#include "common/gbuffer_textures.glsl"
#include "ddgi/sampling.glsl"

uniform vec3 uEye;

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    GBufferTexels t = fetchGBuffer(pixel);
    if (!gbufferHit(t.position)) return;
    GBufferSurface s = decodeGBuffer(t);
    vec3 toViewer = uEye - s.position;
    float len = length(toViewer);
    toViewer = len > 0.0 ? toViewer / len : s.normal;
    vec3 e = ddgiSampleIrradiance(s.position, s.normal, toViewer);
    addToTarget(pixel, vec4(surfaceDiffuseAlbedo(s) * kInvPi * e, 1.0));
}
