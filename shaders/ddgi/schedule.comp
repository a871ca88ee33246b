#version 450 core
// The GPU's probe schedule (ddgi.trace = volume), one thread per probe: each probe's work this
// frame from its state and blends (shared/probe_schedule.h, as the CPU's scheduleProbes), and
// for every probe that blends a job (its tiles, its hysteresis, its ray block) and its traced
// position, appended where the shading, blend and border passes read them; their indirect
// dispatches count the jobs. Nothing goes back to the CPU.
#define DDGI_JOBS_ACCESS
#include "ddgi/blend_common.glsl"
#include "ddgi/probe_layout.glsl"
#include "ddgi/probe_update.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 4) writeonly buffer JobOrigins { vec4 jobOrigins[]; };  // volume_shade.comp's

uniform int uFrame;
uniform int uRays;           // blend rays per probe
uniform bool uClassify;
uniform int uSleepInterval;
uniform float uHysteresis;

void main() {
    int p = int(gl_GlobalInvocationID.x);
    if (p >= uProbeCount) return;
    vec4 data = probeData[p];
    int blends = probeBlends[p];
    // The volume's occupancy tells a sleeping probe whether geometry came near (classify.comp).
    int work = probeWork(uClassify, int(data.w), blends, uFrame, p, uSleepInterval, true);
    probeWorks[p] = work;
    if (work != kProbeWorkFull) return;
    uint j = atomicAdd(updateDispatches[3 * kDdgiDispatchShade + 1], 1u);
    atomicAdd(updateDispatches[3 * kDdgiDispatchBlendIrradiance + 2], 1u);
    atomicAdd(updateDispatches[3 * kDdgiDispatchBlendDistance + 2], 1u);
    atomicAdd(updateDispatches[3 * kDdgiDispatchBorderIrradiance + 2], 1u);
    atomicAdd(updateDispatches[3 * kDdgiDispatchBorderDistance + 2], 1u);
    int v = ddgiVolumeOf(p);
    ivec2 tile = ddgiProbeTile(p);
    BlendJob job;
    job.probe = p;
    job.irradianceX = tile.x * (uIrradianceTexels + 2);
    job.irradianceY = tile.y * (uIrradianceTexels + 2);
    job.distanceX = tile.x * (uDistanceTexels + 2);
    job.distanceY = tile.y * (uDistanceTexels + 2);
    job.rayBase = int(j) * uRays;
    job.hysteresis = probeHysteresis(uHysteresis, blends);
    job.maxDistance = 1.5 * length(uSpacing[v]);  // ProbeVolume::maxDistance
    jobs[j] = job;
    jobOrigins[j] = vec4(ddgiProbeBasePosition(p) + data.xyz, 0.0);
}
