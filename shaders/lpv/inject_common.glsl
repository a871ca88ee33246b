// Shared by the injection vertex shaders: the point handed to inject.geom and the CPU
// injection's arithmetic (gi/lpv/injection.cpp, gi/sh/sh.h) written out operation by operation
// and marked precise, so that a surfel lands in the same cell as on the CPU even when it sits
// on a cell boundary (a wall half a cell from a cell centre, shifted by half a cell).
#ifndef VOXGI_LPV_INJECT_COMMON
#define VOXGI_LPV_INJECT_COMMON

// The constants as the C++ float constants (sh::kY00, sh::kY1, A_0, A_1), set from C++.
uniform vec2 uShY;           // Y00, Y1
uniform vec4 uShCosineLobe;  // A_0, A_1, A_1, A_1
uniform ivec3 uOrigin;       // the cascade's first cell, in world cells
uniform float uCellSize;
uniform int uVolumeSize;     // N for light, N + 1 for the corner-aligned geometry volume

out Injected {
    flat int valid;
    flat ivec3 cell;  // local cell (light) or corner (geometry)
    flat vec4 value0;
    flat vec4 value1;
    flat vec4 value2;
} vOut;

void dropPoint() {
    vOut.valid = 0;
    vOut.cell = ivec3(0);
    vOut.value0 = vOut.value1 = vOut.value2 = vec4(0.0);
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}

void emitPoint(ivec3 cell, vec4 v0, vec4 v1, vec4 v2) {
    bool inside = all(greaterThanEqual(cell, ivec3(0))) && all(lessThan(cell, ivec3(uVolumeSize)));
    vOut.valid = inside ? 1 : 0;
    vOut.cell = cell;
    vOut.value0 = v0;
    vOut.value1 = v1;
    vOut.value2 = v2;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}

// glm's dot and normalize: (x x + y y) + z z, then v * (1 / sqrt(.)).
float dotExact(vec3 a, vec3 b) {
    precise float r = a.x * b.x + a.y * b.y;
    r = r + a.z * b.z;
    return r;
}
vec3 normalizeExact(vec3 v) {
    precise float s = 1.0 / sqrt(dotExact(v, v));
    precise vec3 r = v * s;
    return r;
}

// sh::cosineLobe(n).
vec4 cosineLobeExact(vec3 n) {
    precise vec4 basis = vec4(uShY.x, -uShY.y * n.y, uShY.y * n.z, -uShY.y * n.x);
    precise vec4 lobe = basis * uShCosineLobe;
    return lobe;
}
#endif
