#version 450 core
// Deferred apply of `lpv.transport=ordinates` (gi/lpv/ordinates.h): per pixel, the irradiance a
// receiver facing n gets, from the cell's six axis-facing irradiances (cubeIrradiance, trilinear
// between cells, read from the brick pool: shaders/shared/light_bricks.h), times the diffuse
// albedo / pi. Cascades are read as apply.frag reads the SH
// light: cascade c gives S_c x ring_c + (S_c - S_{c-1}) x inner_c (gi/lpv/cascades.h). Glossy
// surfaces add the finest cascade's march (lpv/glossy_march.glsl).
#include "lpv/cascade_weights.glsl"
#include "shared/constants.h"
#include "shared/irradiance_cube.h"
#include "shared/light_bricks.h"
#include "common/gbuffer_textures.glsl"

#ifdef LPV_TAP_VISIBILITY
#define TRIANGLE_BVH_BINDING 14
#include "common/triangle_bvh.glsl"
uniform float uTapRayOffset;  // rays to the taps leave the surface this far along its normal
#endif
#ifdef LPV_TAP_MASKS
// gi/lpv/tap_masks.h: per cascade (from uMaskBase[c]) and stored cell, where its masks start
// (over 48; ~0u: no surfaces), then from uMasksStart per subcell and side the 27 neighbours its
// surfaces see.
layout(std430, binding = 15) readonly buffer TapMasks { uint tapMasks[]; };
uniform int uMaskBase[kLpvMaxCascades];
uniform int uMasksStart;
#endif
const uint kAllTaps = 0xFFu;

layout(std430, binding = 12) readonly buffer LightBricks { vec4 lightBricks[]; };     // per light set: [face][slot][brick cell]
layout(std430, binding = 13) readonly buffer BrickTables { int brickTables[]; };      // per cascade and brick: slot

uniform float uCellSize[kLpvMaxCascades];
uniform int uTableSide[kLpvMaxCascades];     // bricks per side of each cascade's table
uniform int uTableStart[kLpvMaxCascades];    // where its table starts in brickTables
uniform int uRingSlot[kLpvMaxCascades];      // where its ring and inner light's slots start in the pool
uniform int uInnerSlot[kLpvMaxCascades];
uniform int uSlots[kLpvMaxCascades];         // slots of each of its light sets
uniform int uCascadeCount;
uniform int uResolution;
uniform float uApplyNormalOffset;
uniform int uQuadraticRead;                 // lpv.cube_read: 1 quadratic, 0 ambient cube

layout(location = 0) out vec4 outColor;

// Cell `cell` of cascade c among its slots' cells (brickCell); -1 where its brick is not stored.
int storedCell(int c, ivec3 cell) {
    int slot = brickTables[uTableStart[c] + brickTableIndex(cell, uTableSide[c])];
    return slot < 0 ? -1 : brickCell(slot, cell);
}

// The eight trilinear taps of cascade c around uvw (tap k: i0, or i1 on the axes whose bit of k
// is set) and the weights of the upper ones.
void trilinearTaps(vec3 uvw, out ivec3 i0, out ivec3 i1, out vec3 f) {
    float size = float(uResolution);
    vec3 x = clamp(uvw * size - 0.5, vec3(0.0), vec3(size - 1.0));
    i0 = ivec3(floor(x));
    i1 = min(i0 + 1, ivec3(uResolution - 1));
    f = x - vec3(i0);
}

// lpv.tap_visibility: bit k set where the receiver at `surface` (normal n) sees tap k's cell
// centre, or where that centre lies behind its surface (such cells hold the light that reaches
// the surface from the cell it lies in, and are kept). A thin wall or a stall's panel between
// the receiver and a cell hides that cell's light, which is the light of the panel's other side.
uint visibleTaps(int c, vec3 uvw, vec3 surface, vec3 n) {
#ifdef LPV_TAP_VISIBILITY
    ivec3 i0, i1;
    vec3 f;
    trilinearTaps(uvw, i0, i1, f);
    uint mask = 0u;
    vec3 o = surface + n * uTapRayOffset;
    for (int k = 0; k < 8; ++k) {
        ivec3 tap = mix(i0, i1, bvec3((k & 1) != 0, (k & 2) != 0, (k & 4) != 0));
        if (storedCell(c, tap) < 0) continue;  // not read anyway: no ray
        vec3 centre = uLpvMin[c] + (vec3(tap) + 0.5) * uCellSize[c];
        vec3 d = centre - o;
        float len = length(d);
        BvhHit blocker;
        bool hidden = dot(centre - surface, n) > 0.0 && len > 0.0 && bvhTrace(o, d / len, 0.0, len, true, blocker);
        if (!hidden) mask |= 1u << k;
    }
    return mask;
#elif defined(LPV_TAP_MASKS)
    // The mask of the half cell the surface point lies in, for the side n faces (tapMaskClass);
    // taps beyond its cell's 27 neighbours (an apply offset over half a cell) are kept.
    ivec3 i0, i1;
    vec3 f;
    trilinearTaps(uvw, i0, i1, f);
    vec3 at = (surface - uLpvMin[c]) / uCellSize[c];
    ivec3 home = ivec3(floor(at));
    if (any(lessThan(home, ivec3(0))) || any(greaterThanEqual(home, ivec3(uResolution)))) return kAllTaps;
    int cell = storedCell(c, home);
    if (cell < 0) return kAllTaps;
    uint first = tapMasks[uMaskBase[c] + cell];
    if (first == 0xFFFFFFFFu) return kAllTaps;
    ivec3 sub = clamp(ivec3(floor((at - vec3(home)) * 2.0)), ivec3(0), ivec3(1));
    vec3 a = abs(n);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    uint seen = tapMasks[uint(uMasksStart) + first * 48u + uint((sub.x + 2 * sub.y + 4 * sub.z) * 6 + 2 * axis) +
                         (n[axis] < 0.0 ? 1u : 0u)];
    uint mask = 0u;
    for (int k = 0; k < 8; ++k) {
        ivec3 d = mix(i0, i1, bvec3((k & 1) != 0, (k & 2) != 0, (k & 4) != 0)) - home;
        bool near = all(lessThanEqual(abs(d), ivec3(1)));
        if (!near || ((seen >> ((d.x + 1) + 3 * (d.y + 1) + 9 * (d.z + 1))) & 1u) != 0u) mask |= 1u << k;
    }
    return mask;
#else
    return kAllTaps;
#endif
}

// Irradiance (W/m^2) for normal n: the cell's six faces read as uQuadraticRead says
// (shared/irradiance_cube.h), trilinear between cell centres and clamped at the grid's edge as a
// texture would be (rgb), over the taps in `taps` whose bricks are stored (a: their trilinear
// weight). Receivers read stored cells only (the bricks reach ordinatesReach cells around every
// surface); the glossy march may not.
vec4 cubeIrradiance(int c, int firstSlot, vec3 uvw, vec3 n, uint taps) {
    ivec3 i0, i1;
    vec3 f;
    trilinearTaps(uvw, i0, i1, f);
    CubeWeights w = cubeWeights(n, uQuadraticRead != 0);
    int first = firstSlot * 6 * kBrickCells, slots = uSlots[c];
    vec4 e = vec4(0.0);
    for (int k = 0; k < 8; ++k) {
        if ((taps & (1u << k)) == 0u) continue;
        bvec3 upper = bvec3((k & 1) != 0, (k & 2) != 0, (k & 4) != 0);
        int cell = storedCell(c, mix(i0, i1, upper));
        if (cell < 0) continue;
        vec3 t = mix(1.0 - f, f, upper);
        float weight = t.x * t.y * t.z;
        // The ambient read weighs one face per axis: the other is not loaded.
        vec3 v = vec3(0.0);
        for (int a = 0; a < 3; ++a) {
            if (w.towards[a] != 0.0) v += w.towards[a] * lightBricks[first + brickValue(slots, cell, 2 * a)].rgb;
            if (w.against[a] != 0.0) v += w.against[a] * lightBricks[first + brickValue(slots, cell, 2 * a + 1)].rgb;
        }
        e += weight * vec4(v, 1.0);
    }
    return e;
}

// The stored cells' irradiance, renormalized over their weight.
vec3 storedIrradiance(int c, int firstSlot, vec3 uvw, vec3 n, uint taps) {
    vec4 e = cubeIrradiance(c, firstSlot, uvw, n, taps);
    return e.a > 0.0 ? e.rgb / e.a : vec3(0.0);
}

#include "lpv/glossy_march.glsl"

// A surface facing r collects the radiance around r: its irradiance over pi (a: stored weight).
vec4 glossyCellRadiance(vec3 uvw, vec3 r) {
    vec4 e = cubeIrradiance(0, uRingSlot[0], uvw, r, kAllTaps);
    return e.a > 0.0 ? vec4(e.rgb / e.a * kInvPi, 1.0) : vec4(0.0);
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    GBufferTexels t = fetchGBuffer(pixel);
    if (!gbufferHit(t.position)) { outColor = vec4(0.0); return; }
    GBufferSurface s = decodeGBuffer(t);
    vec3 n = s.normal;
    vec3 e = vec3(0.0);
    float outside = 1.0;  // 1 - S_{c-1}: the share no finer cascade holds
    for (int c = 0; c < uCascadeCount; ++c) {
        vec3 p = s.position + n * (uApplyNormalOffset * uCellSize[c]);
        float w = cascadeInlier(c, p) * outside;  // S_c - S_{c-1}
        float held = 1.0 - outside + w;           // S_c
        vec3 uvw = uvwOf(c, p);
        if (held > 0.0 && all(greaterThanEqual(uvw, vec3(0.0))) && all(lessThanEqual(uvw, vec3(1.0)))) {
            uint taps = visibleTaps(c, uvw, s.position, n);
            e += held * storedIrradiance(c, uRingSlot[c], uvw, n, taps);
            if (c > 0 && w > 0.0) e += w * storedIrradiance(c, uInnerSlot[c], uvw, n, taps);
        }
        outside -= w;
    }
    outColor = vec4(surfaceDiffuseAlbedo(s) * kInvPi * max(e, vec3(0.0)) + glossyReflection(s), 1.0);
}
