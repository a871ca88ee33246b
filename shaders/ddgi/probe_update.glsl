// What the GPU keeps of each probe between frames when the probe states live there
// (ddgi.trace = volume), besides the probe data of probe_layout.glsl: its blends since a reset,
// this frame's work (shared/probe_schedule.h), and the frame's dispatches and counters.
#ifndef VOXGI_DDGI_PROBE_UPDATE_GLSL
#define VOXGI_DDGI_PROBE_UPDATE_GLSL
#include "shared/probe_schedule.h"

layout(std430, binding = 9) buffer ProbeBlends { int probeBlends[]; };
layout(std430, binding = 10) buffer ProbeWorks { int probeWorks[]; };
layout(std430, binding = 11) buffer UpdateCounters { uint updateCounters[kDdgiCounters]; };
layout(std430, binding = 12) buffer UpdateDispatches { uint updateDispatches[3 * kDdgiDispatches]; };

uniform int uProbeCount;
#endif
