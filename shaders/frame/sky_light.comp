#version 450 core
// Light from the sky on every G-buffer surface: diffuse albedo / pi times the irradiance of the
// sky-lighting volume (gi/sky/sky_volume.h, read by common/sky_volume.glsl). Added to the direct
// layer: the path tracer counts the sky after one scattering as direct.
#define SCREEN_PASS_ADDITIVE
#include "common/screen_pass.glsl"
#include "common/gbuffer_textures.glsl"
#include "common/sky_volume.glsl"
#include "shared/constants.h"

void main() {
    ivec2 pixel;
    if (!screenPixel(pixel)) return;
    GBufferTexels t = fetchGBuffer(pixel);
    if (!gbufferHit(t.position)) return;
    GBufferSurface s = decodeGBuffer(t);
    addToTarget(pixel, vec4(surfaceDiffuseAlbedo(s) * kInvPi * skyVolumeIrradiance(s.position, s.normal), 1.0));
}
