#version 450 core
// Relocation and classification on the GPU (ddgi.trace = volume or bvh), one thread per probe
// that the schedule gave work: the CPU's relocateProbes and classifyProbes (gi/ddgi/
// probe_states.cpp) with the fixed rays cast through the NanoVDB geometry volume (through the
// triangles' BVH with DDGI_TRACE_TRIANGLES) instead of by Embree, and the volume's occupancy read
// where the CPU reads the rays' hits: "geometry near" is an occupied voxel within one cell on
// every axis, and relocation keeps the probe min_frontface_distance from the nearest occupied
// voxel (the fixed rays may pass beside a small object). Writes each probe's offset, state and
// blends where the next frame's schedule and every sampling pass read them, and counts the
// states.
#define NANO_GEOMETRY_BINDING 3
#define DDGI_PROBE_DATA_ACCESS
#include "common/nano_geometry.glsl"
#ifdef DDGI_TRACE_TRIANGLES
#define TRIANGLE_BVH_BINDING 14
#include "common/triangle_bvh.glsl"
#endif
#include "ddgi/probe_layout.glsl"
#include "ddgi/probe_update.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 13) readonly buffer FixedDirections { vec4 fixedDirections[]; };

uniform int uFixedRays;  // 0: neither classification nor relocation
uniform bool uClassify;
uniform bool uRelocate;
uniform float uMissDistance;
uniform float uBackfaceThreshold;
uniform float uRelocationBackfaceThreshold;
uniform float uMinFrontfaceDistance;  // in cells of the probe's volume

void main() {
    int p = int(gl_GlobalInvocationID.x);
    if (p >= uProbeCount) return;
    vec4 data = probeData[p];
    int state = int(data.w);
    int work = probeWorks[p];
    if (work == kProbeWorkFixedOnly) atomicAdd(updateCounters[kDdgiCountFixedOnly], 1u);
    if (work != kProbeWorkNone && uFixedRays > 0) {
        int v = ddgiVolumeOf(p);
        vec3 spacing = uSpacing[v];
        vec3 base = ddgiProbeBasePosition(p);
        vec3 offset = data.xyz;
        ProbeHits hits;
        hits.traced = uFixedRays;
        hits.backfaces = 0;
        hits.closestBack = uMissDistance;
        hits.closestFront = uMissDistance;
        hits.closestBackDir = vec3(0.0);
        hits.closestFrontDir = vec3(0.0);
        pnanovdb_readaccessor_t normals = nanoAccessor(uNanoNormalGrid);
        for (int i = 0; i < uFixedRays; ++i) {
            vec3 dir = fixedDirections[i].xyz;
            float t;
#ifdef DDGI_TRACE_TRIANGLES
            BvhHit hit;
            if (!bvhTrace(base + offset, dir, 0.0, uMissDistance, false, hit)) continue;
            t = hit.t;
            bool back = !(dot(bvhGeometricNormal(hit.triangle), dir) < 0.0);
#else
            ivec3 voxel;
            if (!nanoFirstHit(base + offset, dir, 0.0, uMissDistance, t, voxel)) continue;
            vec3 n;
            bool back = nanoBackFace(nanoReadVec3(normals, voxel), dir, n);
#endif
            if (back) {
                ++hits.backfaces;
                if (t < hits.closestBack) {
                    hits.closestBack = t;
                    hits.closestBackDir = dir;
                }
            } else if (t < hits.closestFront) {
                hits.closestFront = t;
                hits.closestFrontDir = dir;
            }
        }
        if (work == kProbeWorkFull && uRelocate) {
            float minFront = uMinFrontfaceDistance * min(spacing.x, min(spacing.y, spacing.z));
            // The nearest occupied voxel counts as a front face, which the fixed rays may pass beside.
            vec3 surface;
            if (nanoNearestOccupied(base + offset, vec3(minFront), false, surface)) {
                float d = distance(surface, base + offset);
                if (d > 0.0 && d < hits.closestFront) {
                    hits.closestFront = d;
                    hits.closestFrontDir = (surface - base - offset) / d;
                }
            }
            offset = relocatedOffset(offset, hits, uRelocationBackfaceThreshold, minFront, spacing);
        }
        int blends = probeBlends[p];
        if (work == kProbeWorkFull) ++blends;
        if (uClassify) {
            vec3 at = base + offset;
            bool inside = float(hits.backfaces) / float(uFixedRays) > uBackfaceThreshold;
            vec3 unused;
            bool near = nanoNearestOccupied(at, spacing, true, unused);
            int next = classifiedState(inside, near);
            if (state == kProbeOff && next != kProbeOff) blends = 0;
            state = next;
        }
        probeBlends[p] = blends;
        probeData[p] = vec4(offset, float(state));
    } else if (work == kProbeWorkFull) {
        probeBlends[p] += 1;
    }
    atomicAdd(updateCounters[kDdgiCountStates + state], 1u);
}
