// The sky-lighting volume (gi/sky/sky_volume.h) as deferred passes read it: irradiance on a
// surface at p with normal n from the cells around p + n * cell / 2, trilinear over the cells
// in open space, through the brick index (SkyVolume::sampleIrradiance is the same on the CPU).
// Bound by
// SkyVolumeTexture::bind (gi/sky/sky_volume_texture.h).
#ifndef VOXGI_SKY_VOLUME_GLSL
#define VOXGI_SKY_VOLUME_GLSL
#include "shared/sky_volume.h"

uniform sampler3D uSkyVolume;   // the stored bricks' atlas, 7 texels per cell along x
uniform isampler3D uSkyBricks;  // every brick's slot in the atlas, -1 where it is empty
uniform vec3 uSkyOrigin;        // centre of cell (0, 0, 0)
uniform float uSkyCellSize;
uniform ivec3 uSkyDims;
uniform int uSkyAtlasColumns;   // bricks per atlas row

// Texel v of cell c's 7; zero (no light, not valid) in an empty brick.
vec4 skyCellTexel(ivec3 c, int v) {
    ivec3 brick = c / kSkyBrickCells;
    int slot = texelFetch(uSkyBricks, brick, 0).r;
    if (slot < 0) return vec4(0.0);
    ivec3 local = c - brick * kSkyBrickCells;
    ivec3 at = ivec3(7 * (kSkyBrickCells * (slot % uSkyAtlasColumns) + local.x) + v, local.y,
                     kSkyBrickCells * (slot / uSkyAtlasColumns) + local.z);
    return texelFetch(uSkyVolume, at, 0);
}

// W/m^2 from the sky on a surface at p facing n.
vec3 skyVolumeIrradiance(vec3 p, vec3 n) {
    SkyVolumeTaps taps = skyVolumeTaps(p + n * (0.5 * uSkyCellSize), uSkyOrigin, uSkyCellSize);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 o = ivec3(corner & 1, (corner >> 1) & 1, corner >> 2);
        ivec3 c = clamp(taps.base + o, ivec3(0), uSkyDims - 1);
        vec3 w3 = mix(vec3(1.0) - taps.fraction, taps.fraction, vec3(o));
        vec4 last = skyCellTexel(c, 6);
        float w = w3.x * w3.y * w3.z * last.w;
        if (!(w > 0.0)) continue;
        sum += w * skyCellIrradiance(skyCellTexel(c, 0), skyCellTexel(c, 1), skyCellTexel(c, 2), skyCellTexel(c, 3),
                                     skyCellTexel(c, 4), skyCellTexel(c, 5), last, n);
        weights += w;
    }
    return weights > 0.0 ? sum / weights : vec3(0.0);
}
#endif
