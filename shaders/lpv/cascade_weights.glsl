// The cascades' weights (gi/lpv/cascades.h: cascadeInlier and sourceShares, where the split of
// the light between cascades is explained), with their uniforms; set by setCascadeUniforms
// (gi/lpv/gl_cascade_uniforms.h).
#ifndef VOXGI_LPV_CASCADE_WEIGHTS
#define VOXGI_LPV_CASCADE_WEIGHTS
#include "lpv/limits.h"

uniform vec3 uLpvMin[kLpvMaxCascades];     // the snapped grid, world space
uniform vec3 uLpvMax[kLpvMaxCascades];
uniform vec3 uLpvExtent[kLpvMaxCascades];  // max - min
uniform vec3 uFadeMin[kLpvMaxCascades];    // the unsnapped bounds the border fade uses
uniform vec3 uFadeMax[kLpvMaxCascades];
uniform float uFadeWidth[kLpvMaxCascades];

vec3 uvwOf(int c, vec3 p) { return (p - uLpvMin[c]) / uLpvExtent[c]; }

// f_c(x): 1 inside, 0 outside the grid, linear across the border band.
float cascadeInlier(int c, vec3 x) {
    if (any(lessThan(x, uLpvMin[c])) || any(greaterThan(x, uLpvMax[c]))) return 0.0;
    if (uFadeWidth[c] <= 0.0) return 1.0;
    vec3 d = min(x - uFadeMin[c], uFadeMax[c] - x);
    return clamp(min(d.x, min(d.y, d.z)) / uFadeWidth[c], 0.0, 1.0);
}

// prod_{j < level} (1 - f_j(x)): the share of x that no cascade finer than `level` holds.
float outsideFiner(int level, vec3 x) {
    float outside = 1.0;
    for (int j = 0; j < level; ++j) outside *= 1.0 - cascadeInlier(j, x);
    return outside;
}
#endif
