#version 450 core
// Deferred LPV apply: per pixel, the irradiance from each cascade's light volume (trilinear SH
// lookup, cosine lobe about -n: light arriving at the front face travels against the normal),
// blended finest-first with each cascade's border fade, times the diffuse albedo / pi.
// Radiance of a cell is its intensity over the cell face area (the seed's A_s / A_c weight).
#include "common/sh.glsl"
#include "lpv/limits.h"
#include "shared/constants.h"
#include "common/gbuffer_textures.glsl"

uniform sampler3D uLpvR[kLpvMaxCascades];
uniform sampler3D uLpvG[kLpvMaxCascades];
uniform sampler3D uLpvB[kLpvMaxCascades];
uniform vec3 uLpvMin[kLpvMaxCascades];
uniform vec3 uLpvExtent[kLpvMaxCascades];
uniform float uCellSize[kLpvMaxCascades];
uniform vec3 uFadeMin[kLpvMaxCascades];
uniform vec3 uFadeMax[kLpvMaxCascades];
uniform float uFadeWidth[kLpvMaxCascades];
uniform int uCascadeCount;
uniform vec3 uEye;
uniform float uApplyNormalOffset;
uniform float uDampening;
uniform int uGlossy;

layout(location = 0) out vec4 outColor;

vec3 uvwOf(int c, vec3 p) { return (p - uLpvMin[c]) / uLpvExtent[c]; }

// The weight of cascade c at p: 1 inside, falling to 0 across the border band.
float inlier(int c, vec3 p) {
    vec3 uvw = uvwOf(c, p);
    if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) return 0.0;
    if (uFadeWidth[c] <= 0.0) return 1.0;
    vec3 d = min(p - uFadeMin[c], uFadeMax[c] - p) / uFadeWidth[c];
    return clamp(min(d.x, min(d.y, d.z)), 0.0, 1.0);
}

// Incident irradiance (W/m^2) at p for normal n from cascade c, with optional dampening.
vec3 irradiance(int c, vec3 p, vec3 n) {
    vec3 uvw = uvwOf(c, p);
    vec4 r = texture(uLpvR[c], uvw), g = texture(uLpvG[c], uvw), b = texture(uLpvB[c], uvw);
    vec3 e = vec3(shConvolveCosine(r, -n), shConvolveCosine(g, -n), shConvolveCosine(b, -n));
    e = max(e, vec3(0.0)) / (uCellSize[c] * uCellSize[c]);
    if (uDampening > 0.0) {
        // Gradient dampening (seed 000): a large change of the SH along the normal means light
        // from behind the surface; damp by the largest relative squared difference.
        vec3 dp = n * (0.5 * uCellSize[c]) / uLpvExtent[c];
        float worst = 0.0;
        vec4 fr = texture(uLpvR[c], uvw + dp) - texture(uLpvR[c], uvw - dp);
        vec4 fg = texture(uLpvG[c], uvw + dp) - texture(uLpvG[c], uvw - dp);
        vec4 fb = texture(uLpvB[c], uvw + dp) - texture(uLpvB[c], uvw - dp);
        worst = max(worst, dot(fr, fr) / max(dot(r, r), 1e-30));
        worst = max(worst, dot(fg, fg) / max(dot(g, g), 1e-30));
        worst = max(worst, dot(fb, fb) / max(dot(b, b), 1e-30));
        e /= 1.0 + uDampening * worst;
    }
    return e;
}

// Glossy: march the finest cascade along the reflected ray, one cell per step, averaging the
// radiance arriving back along it with 1/d^2 weights (seed 000 section 3.10.4).
vec3 glossyRadiance(vec3 p, vec3 r, float roughness) {
    int steps = int(mix(12.0, 4.0, clamp(roughness, 0.0, 1.0)));
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int i = 1; i <= steps; ++i) {
        float d = float(i) * uCellSize[0];
        vec3 q = p + r * d;
        if (inlier(0, q) <= 0.0) break;
        vec3 uvw = uvwOf(0, q);
        vec3 L = vec3(shEvaluate(texture(uLpvR[0], uvw), -r), shEvaluate(texture(uLpvG[0], uvw), -r),
                      shEvaluate(texture(uLpvB[0], uvw), -r));
        float w = 1.0 / (float(i) * float(i));
        sum += max(L, vec3(0.0)) * w;
        weights += w;
    }
    return weights > 0.0 ? sum / (weights * uCellSize[0] * uCellSize[0]) : vec3(0.0);
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    GBufferTexels t = fetchGBuffer(pixel);
    if (!gbufferHit(t.position)) { outColor = vec4(0.0); return; }
    GBufferSurface s = decodeGBuffer(t);
    vec3 n = s.normal;
    vec3 e = vec3(0.0);
    float remaining = 1.0;
    for (int c = 0; c < uCascadeCount && remaining > 0.0; ++c) {
        vec3 p = s.position + n * (uApplyNormalOffset * uCellSize[c]);
        float w = inlier(c, p) * remaining;
        if (w <= 0.0) continue;
        e += w * irradiance(c, p, n);
        remaining -= w;
    }
    vec3 color = diffuseAlbedo(s.albedo, s.metallic, s.specular) * kInvPi * e;
    vec3 f0 = mix(vec3(s.specular), s.albedo, s.metallic);
    if (uGlossy != 0 && max(f0.r, max(f0.g, f0.b)) > 0.0 && s.roughness < 0.6) {
        vec3 v = normalize(uEye - s.position);
        vec3 r = reflect(-v, n);
        vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - max(dot(n, v), 0.0), 5.0);
        color += fresnel * glossyRadiance(s.position + n * (0.5 * uCellSize[0]), r, s.roughness);
    }
    outColor = vec4(color, 1.0);
}
