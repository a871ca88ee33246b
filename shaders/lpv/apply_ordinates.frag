#version 450 core
// Deferred apply of `lpv.transport=ordinates` (gi/lpv/ordinates.h): per pixel, the irradiance a
// receiver facing n gets, blended from the cell's six axis-facing irradiances by n^2 (trilinear
// between cells), times the diffuse albedo / pi. Cascades are read as apply.frag reads the SH
// light: cascade c gives S_c x ring_c + (S_c - S_{c-1}) x inner_c (gi/lpv/cascades.h). Glossy
// surfaces add the finest cascade's march (lpv/glossy_march.glsl).
#include "lpv/cascade_weights.glsl"
#include "shared/constants.h"
#include "common/gbuffer_textures.glsl"

// Per cascade, the six faces' irradiance stacked along z: face f holds texels [f N, (f + 1) N).
uniform sampler3D uRing[kLpvMaxCascades];
uniform sampler3D uInner[kLpvMaxCascades];
uniform float uCellSize[kLpvMaxCascades];
uniform int uCascadeCount;
uniform int uResolution;
uniform float uApplyNormalOffset;

layout(location = 0) out vec4 outColor;

// Face f's irradiance at uvw, filtered within its own block of the stack.
vec3 faceIrradiance(sampler3D cube, int f, vec3 uvw) {
    float n = float(uResolution);
    float z = (float(f) * n + clamp(uvw.z * n, 0.5, n - 0.5)) / (6.0 * n);
    return texture(cube, vec3(uvw.xy, z)).rgb;
}

// Irradiance (W/m^2) for normal n: the three faces n points along, weighted by n^2.
vec3 cubeIrradiance(sampler3D cube, vec3 uvw, vec3 n) {
    vec3 w = n * n;
    return w.x * faceIrradiance(cube, n.x >= 0.0 ? 0 : 1, uvw) + w.y * faceIrradiance(cube, n.y >= 0.0 ? 2 : 3, uvw) +
           w.z * faceIrradiance(cube, n.z >= 0.0 ? 4 : 5, uvw);
}

#include "lpv/glossy_march.glsl"

// A surface facing r collects the radiance around r: its irradiance over pi.
vec3 glossyCellRadiance(vec3 uvw, vec3 r) { return cubeIrradiance(uRing[0], uvw, r) * kInvPi; }

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
            e += held * cubeIrradiance(uRing[c], uvw, n);
            if (c > 0 && w > 0.0) e += w * cubeIrradiance(uInner[c], uvw, n);
        }
        outside -= w;
    }
    outColor = vec4(surfaceDiffuseAlbedo(s) * kInvPi * max(e, vec3(0.0)) + glossyReflection(s), 1.0);
}
