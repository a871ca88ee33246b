#version 450 core
// Light from the sky on every G-buffer surface: diffuse albedo / pi times the irradiance of the
// sky-lighting volume (gi/sky/sky_volume.h) around p + n * cell / 2, trilinear over the cells in
// open space (shaders/shared/sky_volume.h; SkyVolume::sampleIrradiance is the same on the CPU).
// Added to the direct layer: the path tracer counts the sky after one scattering as direct.
#include "common/gbuffer_textures.glsl"
#include "shared/constants.h"
#include "shared/sky_volume.h"

uniform sampler3D uSkyVolume;  // 7 texels per cell along x
uniform vec3 uOrigin;          // centre of cell (0, 0, 0)
uniform float uCellSize;
uniform ivec3 uDims;
layout(location = 0) out vec4 outColor;

vec4 cellTexel(ivec3 c, int v) { return texelFetch(uSkyVolume, ivec3(7 * c.x + v, c.y, c.z), 0); }

void main() {
    GBufferTexels t = fetchGBuffer(ivec2(gl_FragCoord.xy));
    if (!gbufferHit(t.position)) { outColor = vec4(0.0); return; }
    GBufferSurface s = decodeGBuffer(t);
    SkyVolumeTaps taps = skyVolumeTaps(s.position + s.normal * (0.5 * uCellSize), uOrigin, uCellSize);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 o = ivec3(corner & 1, (corner >> 1) & 1, corner >> 2);
        ivec3 c = clamp(taps.base + o, ivec3(0), uDims - 1);
        vec3 w3 = mix(vec3(1.0) - taps.fraction, taps.fraction, vec3(o));
        vec4 last = cellTexel(c, 6);
        float w = w3.x * w3.y * w3.z * last.w;
        if (!(w > 0.0)) continue;
        sum += w * skyCellIrradiance(cellTexel(c, 0), cellTexel(c, 1), cellTexel(c, 2), cellTexel(c, 3), cellTexel(c, 4),
                                     cellTexel(c, 5), last, s.normal);
        weights += w;
    }
    vec3 e = weights > 0.0 ? sum / weights : vec3(0.0);
    outColor = vec4(diffuseAlbedo(s.albedo, s.metallic, s.specular) * kInvPi * e, 1.0);
}
