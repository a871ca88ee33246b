#version 450 core
// Rays through the triangles' BVH (common/triangle_bvh.glsl), one thread per ray, written as
// volume_rays.comp writes the volume's hits: the signed hit distance (negative for a back face,
// the miss distance for a miss), the interpolated vertex normal facing the ray (zero for misses
// and back faces), the triangle's diffuse albedo, and the triangle (leaf order) as int bits,
// -1 for a miss. For benchmarks and tests: the Embree probe trace is its reference.
#define TRIANGLE_BVH_BINDING 0
#include "common/triangle_bvh.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 1) readonly buffer Rays { vec4 rays[]; };  // per ray: origin, tMax; direction, tMin
layout(std430, binding = 2) writeonly buffer Hits { vec4 hits[]; };  // per ray: normal, signed distance; albedo, triangle

uniform int uRayCount;
uniform float uMissDistance;

void main() {
    int ray = int(gl_GlobalInvocationID.x);
    if (ray >= uRayCount) return;
    vec4 a = rays[2 * ray], b = rays[2 * ray + 1];
    BvhHit hit;
    if (!bvhTrace(a.xyz, b.xyz, b.w, a.w, false, hit)) {
        hits[2 * ray] = vec4(0.0, 0.0, 0.0, uMissDistance);
        hits[2 * ray + 1] = vec4(0.0, 0.0, 0.0, intBitsToFloat(-1));
        return;
    }
    bool back = !(dot(bvhGeometricNormal(hit.triangle), b.xyz) < 0.0);
    vec3 n = bvhShadingNormal(hit);
    if (dot(n, b.xyz) > 0.0) n = -n;
    hits[2 * ray] = vec4(back ? vec3(0.0) : n, back ? -hit.t : hit.t);
    hits[2 * ray + 1] = vec4(bvhAlbedo(hit.triangle), intBitsToFloat(hit.triangle));
}
