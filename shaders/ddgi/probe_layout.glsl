// Where DDGI's probes are: the field's volumes as uniforms (set by bindProbeField, gi/ddgi/
// ddgi_gpu.cpp) and each probe's relocation offset and state; the CPU side is gi/ddgi/
// probe_field.h. Define DDGI_PROBE_DATA_ACCESS (empty) before including to write the probe data.
#ifndef VOXGI_DDGI_PROBE_LAYOUT_GLSL
#define VOXGI_DDGI_PROBE_LAYOUT_GLSL
#include "ddgi/limits.h"

uniform int uVolumeCount;
uniform ivec3 uCounts[kDdgiMaxVolumes];
uniform vec3 uSpacing[kDdgiMaxVolumes];
uniform vec3 uOrigin[kDdgiMaxVolumes];
uniform ivec3 uScroll[kDdgiMaxVolumes];
uniform int uProbeBase[kDdgiMaxVolumes];
uniform int uTileRow[kDdgiMaxVolumes];
uniform int uIrradianceTexels;
uniform int uDistanceTexels;
#ifndef DDGI_PROBE_DATA_ACCESS
#define DDGI_PROBE_DATA_ACCESS readonly
#endif
layout(std430, binding = 5) DDGI_PROBE_DATA_ACCESS buffer ProbeData { vec4 probeData[]; };  // xyz offset, w state

ivec3 ddgiPositiveMod(ivec3 a, ivec3 n) { return ((a % n) + n) % n; }

// The volume holding global probe `probe` (ProbeField::volumeOf).
int ddgiVolumeOf(int probe) {
    for (int v = uVolumeCount - 1; v > 0; --v)
        if (probe >= uProbeBase[v]) return v;
    return 0;
}

// Storage coordinates of a probe's index within its volume (ProbeVolume::storageFromLocal).
ivec3 ddgiStorageOf(int v, int local) {
    ivec3 c = uCounts[v];
    return ivec3(local % c.x, local / (c.x * c.z), (local / c.x) % c.z);
}

// A probe's position before relocation (ProbeVolume::basePosition of its logical cell).
vec3 ddgiProbeBasePosition(int probe) {
    int v = ddgiVolumeOf(probe);
    ivec3 logical = ddgiPositiveMod(ddgiStorageOf(v, probe - uProbeBase[v]) - uScroll[v], uCounts[v]);
    return uOrigin[v] + vec3(logical) * uSpacing[v];
}

// A probe's tile in the atlases, in tiles (ProbeVolume::tile); times (texels + 2) for texels.
ivec2 ddgiProbeTile(int probe) {
    int v = ddgiVolumeOf(probe);
    ivec3 s = ddgiStorageOf(v, probe - uProbeBase[v]);
    return ivec2(s.x + uCounts[v].x * s.z, uTileRow[v] + s.y);
}
#endif
