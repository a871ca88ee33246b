#version 450 core
// The nearest (smallest) depth of each kSunTileTexels-square tile of each sun cascade: one
// workgroup per tile, 2 x 2 texels per invocation, then a reduction in shared memory. The soft
// shadows' blocker search reads it to bound how far off a caster can be (frame/sun_shadow.glsl).
#include "shared/sun_shadow.h"

layout(local_size_x = 16, local_size_y = 16) in;

uniform sampler2DArray uSunDepth;  // raw depths
layout(r32f, binding = 0) uniform writeonly image2DArray uTileDepth;

shared float nearest[256];

void main() {
    ivec3 tile = ivec3(gl_WorkGroupID);
    ivec2 base = tile.xy * kSunTileTexels + 2 * ivec2(gl_LocalInvocationID.xy);
    float m = 1.0;
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) m = min(m, texelFetch(uSunDepth, ivec3(base + ivec2(x, y), tile.z), 0).r);
    uint i = gl_LocalInvocationIndex;
    nearest[i] = m;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1) {
        if (i < stride) nearest[i] = min(nearest[i], nearest[i + stride]);
        barrier();
    }
    if (i == 0u) imageStore(uTileDepth, tile, vec4(nearest[0]));
}
