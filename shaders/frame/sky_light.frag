#version 450 core
// Light from the sky on every G-buffer surface: diffuse albedo / pi times the irradiance of the
// sky-lighting volume (gi/sky/sky_volume.h, read by common/sky_volume.glsl). Added to the direct
// layer: the path tracer counts the sky after one scattering as direct.
#include "common/gbuffer_textures.glsl"
#include "common/sky_volume.glsl"
#include "shared/constants.h"

layout(location = 0) out vec4 outColor;

void main() {
    GBufferTexels t = fetchGBuffer(ivec2(gl_FragCoord.xy));
    if (!gbufferHit(t.position)) { outColor = vec4(0.0); return; }
    GBufferSurface s = decodeGBuffer(t);
    outColor = vec4(surfaceDiffuseAlbedo(s) * kInvPi * skyVolumeIrradiance(s.position, s.normal), 1.0);
}
