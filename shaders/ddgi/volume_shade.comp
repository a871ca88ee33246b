#version 450 core
// DDGI's blend rays traced and shaded on the GPU (ddgi.trace = volume or bvh), one thread per
// ray of one blend job (workgroup y = job), written where blend.comp reads them: rgb radiance
// toward the probe, a signed hit distance. A front-face hit reflects the frame's lights (shadow
// rays through the same geometry) and the previous frame's probe irradiance times ddgi.energy
// and the sky volume's irradiance (when the frame lights surfaces with it; misses then bring no
// sky) over a Lambert lobe, as the CPU reference does (gi/ddgi/hit_shading.cpp).
// - volume: rays march the NanoVDB geometry volume; the hit is where the ray meets the plane of
//   the surface in the first occupied voxel (its mean normal and surface offset), within it.
// - bvh (DDGI_TRACE_TRIANGLES): rays traverse the triangles' BVH; the hit shades with the
//   interpolated vertex normal, the triangle's emission and its mean diffuse albedo.
#ifdef DDGI_TRACE_TRIANGLES
#define TRIANGLE_BVH_BINDING 3
#include "common/triangle_bvh.glsl"
uniform float uShadowOffset;  // gi/raytrace/ray_tracer.h's surfaceRayOffset
#else
#define NANO_GEOMETRY_BINDING 3
#include "common/nano_geometry.glsl"
#endif
#include "common/sky.glsl"
#include "common/sky_volume.glsl"
#include "ddgi/blend_common.glsl"
#include "ddgi/sampling.glsl"
#include "shared/constants.h"
#include "shared/light_model.h"

layout(local_size_x = 64) in;
layout(std430, binding = 1) readonly buffer Directions { vec4 directions[]; };  // blend rays, unrotated
uniform mat3 uRayRotation;  // this frame's (gi/ddgi/probe_rays.h, RaySet::rotation)
layout(std430, binding = 2) writeonly buffer Rays { vec4 rayValues[]; };  // rgb radiance, a signed distance
layout(std430, binding = 4) readonly buffer JobOrigins { vec4 jobOrigins[]; };  // per job: probe position
layout(std430, binding = 6) readonly buffer Lights { PackedLight lights[]; };

uniform int uRays;
uniform int uLightCount;
uniform int uQuadSampleSets;  // kQuadSampleSets, or 0 without quad lights (the sample is then the centre)
// gi/ddgi/hit_shading.h's quadLightSamples: row k's ray i is fract(uQuadStart[k] + i * uR2Step).
uniform vec2 uQuadStart[kDdgiQuadSampleSets];
uniform vec2 uR2Step;
uniform float uMissDistance;
uniform float uEnergy;
uniform bool uSkyAtMisses;   // gi/ddgi/hit_shading.h, ProbeSky
uniform bool uSkyVolumeLit;  // hits add common/sky_volume.glsl's irradiance
// Shadow rays leave this many voxels off the hit along its normal, and stop short of the light:
// a point or spot light may sit anywhere in an occupied voxel (a lamp's), which the ray enters
// up to a voxel diagonal before it; a quad light lies on a voxelized surface (a ceiling) whose
// voxels a slanted ray meets farther out.
const float kShadowOffsetVoxels = 1.5;
const float kShadowStopPointVoxels = 1.75;
const float kShadowStopQuadVoxels = 3.0;

// Irradiance from the frame's lights at (p, n) with shadow rays from `shadowOrigin`.
vec3 lightsIrradiance(vec3 p, vec3 n, vec2 u) {
    vec3 e = vec3(0.0);
    for (int l = 0; l < uLightCount; ++l) {
        IncidentLight incident = evaluateLight(lights[l], p, u);
        if (!(incident.falloff > 0.0)) continue;
        float c = dot(n, incident.direction);
        if (!(c > 0.0)) continue;
        bool infinite = isinf(incident.distance);
#ifdef DDGI_TRACE_TRIANGLES
        // As ShadowRayVisibility: off the surface by the offset, short of the light by a
        // 1e-4 of its distance (a quad light's own triangles are not blockers).
        float tMax = infinite ? 1e30 : incident.distance * (1.0 - 1e-4) - uShadowOffset;
        BvhHit blocker;
        if (tMax > 0.0 && bvhTrace(p + n * uShadowOffset, incident.direction, 0.0, tMax, true, blocker)) continue;
#else
        float stop = lights[l].kind.x == kLightQuad ? kShadowStopQuadVoxels : kShadowStopPointVoxels;
        float tMax = infinite ? uMissDistance : incident.distance - stop * uNanoVoxelSize;
        float tBlock;
        ivec3 blocker;
        if (tMax > 0.0 &&
            nanoFirstHit(p + n * (kShadowOffsetVoxels * uNanoVoxelSize), incident.direction, 0.0, tMax, tBlock, blocker))
            continue;
#endif
        e += incident.irradiance * c;
    }
    return e;
}

void main() {
    int ray = int(gl_GlobalInvocationID.x);
    if (ray >= uRays) return;
    BlendJob job = jobs[gl_WorkGroupID.y];
    int out_ = job.rayBase + ray;
    vec3 origin = jobOrigins[gl_WorkGroupID.y].xyz;
    vec3 dir = normalize(uRayRotation * directions[ray].xyz);
    float t;
    vec3 n, albedo, emission = vec3(0.0);
#ifdef DDGI_TRACE_TRIANGLES
    BvhHit hit;
    bool found = bvhTrace(origin, dir, 0.0, uMissDistance, false, hit);
    t = hit.t;
    if (found) {
        if (!(dot(bvhGeometricNormal(hit.triangle), dir) < 0.0)) {  // a back face carries no light
            rayValues[out_] = vec4(0.0, 0.0, 0.0, -t);
            return;
        }
        n = bvhShadingNormal(hit);
        if (dot(n, dir) > 0.0) n = -n;
        albedo = bvhAlbedo(hit.triangle);
        emission = bvhEmission(hit.triangle);
    }
#else
    ivec3 voxel;
    bool found = nanoFirstHit(origin, dir, 0.0, uMissDistance, t, voxel);
    if (found) {
        pnanovdb_readaccessor_t normals = nanoAccessor(uNanoNormalGrid);
        if (nanoBackFace(nanoReadVec3(normals, voxel), dir, n)) {  // a back face carries no light
            rayValues[out_] = vec4(0.0, 0.0, 0.0, -t);
            return;
        }
        pnanovdb_readaccessor_t albedos = nanoAccessor(uNanoAlbedoGrid);
        albedo = nanoReadVec3(albedos, voxel);
    }
#endif
    if (!found) {
        rayValues[out_] = vec4(uSkyAtMisses ? skyRadiance(dir) : vec3(0.0), uMissDistance);
        return;
    }
    if (albedo == vec3(0.0)) {
        rayValues[out_] = vec4(emission, t);
        return;
    }
    vec3 p = origin + t * dir;
    vec2 u = uQuadSampleSets > 0 ? fract(uQuadStart[job.probe % uQuadSampleSets] + float(ray) * uR2Step) : vec2(0.5);
    vec3 e = lightsIrradiance(p, n, u);
    if (uEnergy > 0.0) e += uEnergy * ddgiSampleIrradiance(p, n, -dir);
    if (uSkyVolumeLit) e += skyVolumeIrradiance(p, n);
    rayValues[out_] = vec4(emission + albedo * kInvPi * e, t);
}
