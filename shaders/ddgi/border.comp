#version 450 core
// Refreshes the one-texel border of each blended probe tile (workgroup z = job) so bilinear
// lookups continue across the octahedral edges. Same mapping as oct::borderSource.
#include "common/octahedral.glsl"
#include "ddgi/blend_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform image2D uAtlas;
uniform int uTexels;
uniform int uDistance;

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    int n = uTexels;
    if (t.x > n + 1 || t.y > n + 1) return;
    if (t.x > 0 && t.y > 0 && t.x <= n && t.y <= n) return;
    BlendJob job = jobs[gl_WorkGroupID.z];
    ivec2 origin = uDistance != 0 ? ivec2(job.distanceX, job.distanceY) : ivec2(job.irradianceX, job.irradianceY);
    imageStore(uAtlas, origin + t, imageLoad(uAtlas, origin + octBorderSource(t, n)));
}
