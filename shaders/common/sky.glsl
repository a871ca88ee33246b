// The sky's radiance toward a direction, from the table SceneGpu::skyTexture uploads: the
// texels and weights of shaders/shared/sky.h, fetched exactly (no hardware filtering), so the
// GPU reads the values the path tracer reads.
#include "shared/sky.h"

uniform sampler2D uSkyTable;

vec3 skyRadiance(vec3 towardSky) {
    ivec2 size = textureSize(uSkyTable, 0);
    SkyTaps t = skyTaps(towardSky, size.x, size.y);
    return skyBlend(texelFetch(uSkyTable, ivec2(t.texels.x, t.texels.z), 0).rgb,
                    texelFetch(uSkyTable, ivec2(t.texels.y, t.texels.z), 0).rgb,
                    texelFetch(uSkyTable, ivec2(t.texels.x, t.texels.w), 0).rgb,
                    texelFetch(uSkyTable, ivec2(t.texels.y, t.texels.w), 0).rgb, t.fraction);
}
