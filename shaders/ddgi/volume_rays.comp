#version 450 core
// Rays through the NanoVDB geometry volume, one thread per ray: the first occupied voxel's
// entry distance (signed: negative for a back face, nanoBackFace), its unit normal (zero for
// misses and back faces) and albedo. The Embree probe trace
// (gi/ddgi/probe_rays.cpp) is the reference it is tested against.
#define NANO_GEOMETRY_BINDING 0
#include "common/nano_geometry.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 1) readonly buffer Rays { vec4 rays[]; };  // per ray: origin, tMax; direction, tMin
layout(std430, binding = 2) writeonly buffer Hits { vec4 hits[]; };  // per ray: normal, signed distance; albedo, 0

uniform int uRayCount;
uniform float uMissDistance;

void main() {
    int ray = int(gl_GlobalInvocationID.x);
    if (ray >= uRayCount) return;
    vec4 a = rays[2 * ray], b = rays[2 * ray + 1];
    float t;
    ivec3 voxel;
    if (!nanoFirstHit(a.xyz, b.xyz, b.w, a.w, t, voxel)) {
        hits[2 * ray] = vec4(0.0, 0.0, 0.0, uMissDistance);
        hits[2 * ray + 1] = vec4(0.0);
        return;
    }
    pnanovdb_readaccessor_t normals = nanoAccessor(uNanoNormalGrid);
    pnanovdb_readaccessor_t albedos = nanoAccessor(uNanoAlbedoGrid);
    vec3 n;
    bool back = nanoBackFace(nanoReadVec3(normals, voxel), b.xyz, n);
    hits[2 * ray] = vec4(back ? vec3(0.0) : n, back ? -t : t);
    hits[2 * ray + 1] = vec4(nanoReadVec3(albedos, voxel), 0.0);
}
