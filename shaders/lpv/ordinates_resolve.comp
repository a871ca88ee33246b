#version 450 core
// The irradiance cube the apply pass reads (apply_ordinates.frag): each face's three axis
// groups (ordinates_sweep.comp) summed into the volume's slots of the brick pool
// (shaders/shared/light_bricks.h), value by value: 6 x slots work groups of 512 invocations.
layout(local_size_x = 512) in;

#include "shared/light_bricks.h"

layout(std430, binding = 6) readonly buffer Irradiance { vec4 irradiance[]; };  // [axis][face][slot][brick cell]
layout(std430, binding = 12) writeonly buffer Pool { vec4 pool[]; };           // per light set: [face][slot][brick cell]

uniform int uSlots;      // the volume's slots (work groups along y)
uniform int uFirstSlot;  // where they start in the pool

void main() {
    int values = uSlots * 6 * kBrickCells;
    int i = (int(gl_WorkGroupID.y) * 6 + int(gl_WorkGroupID.x)) * kBrickCells + int(gl_LocalInvocationID.x);
    vec4 e = irradiance[i] + irradiance[values + i] + irradiance[2 * values + i];
    pool[uFirstSlot * 6 * kBrickCells + i] = vec4(e.rgb, 0.0);
}
