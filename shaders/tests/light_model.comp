#version 450 core
// Test kernel: the shared light model in GLSL, for comparison with its C++ compilation
// (tests/test_light_model.cpp). Query i: queries[2i] = (receiver xyz, light index),
// queries[2i + 1] = (quad sample uv, 0, 0); result[2i] = (direction, distance),
// result[2i + 1] = (irradiance, falloff).
#include "shared/light_model.h"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Lights { PackedLight lights[]; };
layout(std430, binding = 1) readonly buffer Queries { vec4 queries[]; };
layout(std430, binding = 2) writeonly buffer Results { vec4 results[]; };
uniform int uCount;
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(uCount)) return;
    vec4 q = queries[2u * i];
    IncidentLight incident = evaluateLight(lights[int(q.w)], q.xyz, queries[2u * i + 1u].xy);
    results[2u * i] = vec4(incident.direction, incident.distance);
    results[2u * i + 1u] = vec4(incident.irradiance, incident.falloff);
}
