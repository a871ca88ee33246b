#version 450 core
// One slab step of every bin's sweep (gi/lpv/ordinates.cpp, OrdinatesTransport::sweep; the same
// math in the same order per bin): invocation (x, y) is a lateral cell of the sweep box, z a
// pyramid of bins (axis and sign), whose bins run one after the other. Pyramids of one axis write their own
// group of the irradiance and reflection buffers: the +axis and -axis pyramids step through
// different planes, so no two invocations of a dispatch add to the same value, except at the step
// where both reach the sweep box's middle plane (an odd number of planes), which the host runs as
// two dispatches, one per sign (uSigns).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "shared/light_bricks.h"
#include "shared/ordinate_taps.h"

layout(std430, binding = 0) readonly buffer BinTaps { vec4 binTaps[]; };      // per bin
// The brick table (per brick: slot, -1: none), then per slot and brick cell a surface index, -1: none.
layout(std430, binding = 1) readonly buffer SurfaceOf { int surfaceOf[]; };
// [3s] (m, 0), [3s+1] (clutter shadow per axis, 0), [3s+2] (albedo, 0)
layout(std430, binding = 2) readonly buffer Surfaces { vec4 surfaces[]; };
layout(std430, binding = 3) readonly buffer Sources { float sources[]; };     // [bin][surface][rgb]
layout(std430, binding = 4) readonly buffer PrevParts { vec4 prevParts[]; };  // [bin][padded cell][tap]
layout(std430, binding = 5) writeonly buffer CurParts { vec4 curParts[]; };
layout(std430, binding = 6) buffer Irradiance { vec4 irradiance[]; };          // [axis][face][slot][brick cell]
layout(std430, binding = 7) buffer Reflected { vec4 reflected[]; };            // [axis][surface][face]

uniform int uN;
uniform int uTableSide;        // bricks per side (gi/lpv/brick_map.h)
uniform int uBrickCellsStart;  // where the slots' surface indices start in SurfaceOf
uniform int uSlots;
uniform int uStep;      // slabs into the sweep box along the pyramid's axis
uniform int uSigns;     // which pyramids run: bit 0 the +axis ones, bit 1 the -axis ones
uniform ivec3 uBoxMin;  // the sweep box (OrdinatesTransport::sweepBox), inclusive
uniform ivec3 uBoxMax;
uniform int uBinsPerPyramid;
uniform int uSurfaces;
uniform int uOcclusion;
uniform float uPerArea;  // 1 / h^2

int gAxis, gU, gV, gValues;
ivec3 gMove[4];

vec3 crossedBy(int j, vec3 perAxis) { return crossedBy(j, perAxis, gAxis, gU, gV); }

// cell: the cell among the slots' cells (brickCell; face f at brickValue).
void reflectAt(int s, int j, vec3 hit, vec3 parts, int cell, bool countIrradiance) {
    float total = parts.x + parts.y + parts.z;
    vec3 r = surfaces[3 * s + 2].rgb * hit;
    int axes[3] = int[3](gAxis, gU, gV);
    for (int c = 0; c < 3; ++c) {
        float share = total > 0.0 ? parts[c] / total : (c == 0 ? 1.0 : 0.0);
        if (share <= 0.0) continue;
        int ax = axes[c];
        int face = 2 * ax + (gMove[j][ax] > 0 ? 1 : 0);
        reflected[(gAxis * uSurfaces + s) * 6 + face] += vec4(r * share, 0.0);
        if (countIrradiance) irradiance[gAxis * gValues + brickValue(uSlots, cell, face)] += vec4(hit * (share * uPerArea), 0.0);
    }
}

void main() {
    int n = uN;
    int pyramid = int(gl_GlobalInvocationID.z);
    if (pyramid >= 6 || ((uSigns >> (pyramid % 2)) & 1) == 0) return;
    gAxis = pyramid / 2;
    gU = (gAxis + 1) % 3;
    gV = (gAxis + 2) % 3;
    int x = uBoxMin[gU] + int(gl_GlobalInvocationID.x), y = uBoxMin[gV] + int(gl_GlobalInvocationID.y);
    if (x > uBoxMax[gU] || y > uBoxMax[gV] || uStep > uBoxMax[gAxis] - uBoxMin[gAxis]) return;
    gValues = uSlots * 6 * kBrickCells;
    int sign = pyramid % 2 == 0 ? 1 : -1;
    int a = sign > 0 ? uBoxMin[gAxis] + uStep : uBoxMax[gAxis] - uStep;
    ivec3 local;
    local[gAxis] = a;
    local[gU] = x;
    local[gV] = y;
    // Outside the bricks no receiver reads and no surface is: the light only moves on.
    int slot = surfaceOf[brickTableIndex(local, uTableSide)];
    int cell = slot < 0 ? -1 : brickCell(slot, local);
    int row = n + 2, plane = row * row;
    int here = (y + 1) * row + x + 1;
    int s = slot < 0 ? -1 : surfaceOf[uBrickCellsStart + cell];
    for (int q = 0; q < uBinsPerPyramid; ++q) {
        int k = pyramid * uBinsPerPyramid + q;
        vec4 taps = binTaps[2 * k];
        ivec2 step = ivec2(binTaps[2 * k + 1].xy);
        int su = step.x, sv = step.y;
        for (int j = 0; j < 4; ++j) {
            gMove[j] = ivec3(0);
            gMove[j][gAxis] = sign;
            if ((j & 1) != 0) gMove[j][gU] = su;
            if ((j & 2) != 0) gMove[j][gV] = sv;
        }
        int from[4] = int[4](0, -su, -sv * row, -su - sv * row);
        vec3 part[4];
        for (int j = 0; j < 4; ++j) part[j] = prevParts[(k * plane + here + from[j]) * 4 + j].rgb;
        vec3 inLight = part[0] + part[1] + part[2] + part[3];
        vec3 outLight = inLight;
        bool lit = inLight != vec3(0.0);
        if (lit && slot >= 0) {
            int slabFace = 2 * gAxis + (sign > 0 ? 1 : 0), uFace = 2 * gU + (su > 0 ? 1 : 0), vFace = 2 * gV + (sv > 0 ? 1 : 0);
            int at = gAxis * gValues;
            irradiance[at + brickValue(uSlots, cell, slabFace)] += vec4(inLight * uPerArea, 0.0);
            irradiance[at + brickValue(uSlots, cell, uFace)] += vec4((part[1] + part[3]) * uPerArea, 0.0);
            irradiance[at + brickValue(uSlots, cell, vFace)] += vec4((part[2] + part[3]) * uPerArea, 0.0);
        }
        int out0 = (k * plane + here) * 4;
        if (s < 0) {
            for (int j = 0; j < 4; ++j) curParts[out0 + j] = vec4(taps[j] * outLight, 0.0);
            continue;
        }
        vec3 m = surfaces[3 * s].xyz;
        if (uOcclusion != 0 && lit) {
            vec3 shadow = surfaces[3 * s + 1].xyz;
            for (int j = 0; j < 4; ++j) {
                if (part[j] == vec3(0.0)) continue;
                vec3 crossed = enteringStop(j, abs(m), shadow, gAxis, gU, gV);
                float stopped = min(crossed.x + crossed.y + crossed.z, 1.0);
                if (stopped <= 0.0) continue;
                vec3 hit = part[j] * stopped;
                outLight -= hit;
                reflectAt(s, j, hit, crossed, cell, false);
            }
        }
        int src = (k * uSurfaces + s) * 3;
        outLight += vec3(sources[src], sources[src + 1], sources[src + 2]);
        for (int j = 0; j < 4; ++j) {
            vec3 go = taps[j] * outLight;
            if (uOcclusion != 0 && go != vec3(0.0)) {
                vec3 facing = crossedBy(j, max(-m * vec3(gMove[j]), vec3(0.0)));
                float stopped = min(facing.x + facing.y + facing.z, 1.0);
                if (stopped > 0.0) {
                    reflectAt(s, j, go * stopped, facing, cell, true);
                    go *= 1.0 - stopped;
                }
            }
            curParts[out0 + j] = vec4(go, 0.0);
        }
    }
}
