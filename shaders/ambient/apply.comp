#version 450 core
// Ambient baseline: every visible surface receives the same irradiance E from all directions,
// so its indirect outgoing radiance is the diffuse albedo / pi times E (no occlusion, no
// colour bleeding: the floor a GI method has to beat).
#define SCREEN_PASS_ADDITIVE
#include "common/screen_pass.glsl"
#include "shared/constants.h"
#include "shared/gbuffer.h"

uniform sampler2D uPosition;
uniform sampler2D uAlbedo;
uniform sampler2D uEmission;
uniform vec3 uIrradiance;

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    const vec4 position = texelFetch(uPosition, pixel, 0);
    if (!gbufferHit(position)) return;
    vec3 diffuse = gbufferDiffuseAlbedo(position, texelFetch(uAlbedo, pixel, 0), texelFetch(uEmission, pixel, 0));
    addToTarget(pixel, vec4(diffuse * kInvPi * uIrradiance, 1.0));
}
