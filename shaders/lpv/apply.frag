#version 450 core
// Deferred LPV apply: per pixel, the irradiance from each cascade's light (trilinear SH lookup,
// cosine lobe about -n: light arriving at the front face travels against the normal), times
// the diffuse albedo / pi. Cascade c is read as S_c x ring_c + (S_c - S_{c-1}) x inner_c: near
// light from the finest cascade holding it, far light from the coarser ones (gi/lpv/cascades.h).
// Radiance of a cell is its intensity over the cell face area (the seed's A_s / A_c weight).
#include "common/sh.glsl"
#include "lpv/cascade_weights.glsl"
#include "shared/constants.h"
#include "common/gbuffer_textures.glsl"

uniform sampler3D uLpvR[kLpvMaxCascades];
uniform sampler3D uLpvG[kLpvMaxCascades];
uniform sampler3D uLpvB[kLpvMaxCascades];
// The inner volumes of cascades 1.. (cascade 0 has none): [c - 1].
uniform sampler3D uInnerR[kLpvMaxCascades - 1];
uniform sampler3D uInnerG[kLpvMaxCascades - 1];
uniform sampler3D uInnerB[kLpvMaxCascades - 1];
uniform float uCellSize[kLpvMaxCascades];
uniform int uCascadeCount;
uniform float uApplyNormalOffset;
uniform float uDampening;

layout(location = 0) out vec4 outColor;

// Cascade c's light at uvw: ringWeight x ring + innerWeight x inner, per colour.
void fetchLight(int c, vec3 uvw, float ringWeight, float innerWeight, out vec4 r, out vec4 g, out vec4 b) {
    r = ringWeight * texture(uLpvR[c], uvw);
    g = ringWeight * texture(uLpvG[c], uvw);
    b = ringWeight * texture(uLpvB[c], uvw);
    if (c == 0 || innerWeight <= 0.0) return;
    r += innerWeight * texture(uInnerR[c - 1], uvw);
    g += innerWeight * texture(uInnerG[c - 1], uvw);
    b += innerWeight * texture(uInnerB[c - 1], uvw);
}

// Incident irradiance (W/m^2) at p for normal n from cascade c, with optional dampening.
vec3 irradiance(int c, vec3 p, vec3 n, float ringWeight, float innerWeight) {
    vec3 uvw = uvwOf(c, p);
    if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) return vec3(0.0);
    vec4 r, g, b;
    fetchLight(c, uvw, ringWeight, innerWeight, r, g, b);
    vec3 e = vec3(shConvolveCosine(r, -n), shConvolveCosine(g, -n), shConvolveCosine(b, -n));
    e = max(e, vec3(0.0)) / (uCellSize[c] * uCellSize[c]);
    if (uDampening > 0.0) {
        // Gradient dampening (seed 000): a large change of the SH along the normal means light
        // from behind the surface; damp by the largest relative squared difference.
        vec3 dp = n * (0.5 * uCellSize[c]) / uLpvExtent[c];
        vec4 r0, g0, b0, r1, g1, b1;
        fetchLight(c, uvw + dp, ringWeight, innerWeight, r1, g1, b1);
        fetchLight(c, uvw - dp, ringWeight, innerWeight, r0, g0, b0);
        vec4 fr = r1 - r0, fg = g1 - g0, fb = b1 - b0;
        float worst = 0.0;
        worst = max(worst, dot(fr, fr) / max(dot(r, r), 1e-30));
        worst = max(worst, dot(fg, fg) / max(dot(g, g), 1e-30));
        worst = max(worst, dot(fb, fb) / max(dot(b, b), 1e-30));
        e /= 1.0 + uDampening * worst;
    }
    return e;
}

#include "lpv/glossy_march.glsl"

// The SH intensity travelling along -r over the cell's face area (every cell is stored).
vec4 glossyCellRadiance(vec3 uvw, vec3 r) {
    return vec4(vec3(shEvaluate(texture(uLpvR[0], uvw), -r), shEvaluate(texture(uLpvG[0], uvw), -r),
                     shEvaluate(texture(uLpvB[0], uvw), -r)) / (uCellSize[0] * uCellSize[0]), 1.0);
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
        // Far light (the ring) counts wherever a finer cascade holds the point; the light of
        // finer cascades' surfaces (inner) only where this cascade is the point's own.
        if (held > 0.0) e += irradiance(c, p, n, held, w);
        outside -= w;
    }
    vec3 color = surfaceDiffuseAlbedo(s) * kInvPi * e;
    color += glossyReflection(s);
    outColor = vec4(color, 1.0);
}
