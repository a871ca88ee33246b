// Irradiance from the DDGI probe field; the CPU reference is gi/ddgi/probe_sampling.cpp.
#ifndef VOXGI_DDGI_SAMPLING_GLSL
#define VOXGI_DDGI_SAMPLING_GLSL
#include "common/octahedral.glsl"
#include "ddgi/probe_layout.glsl"

uniform float uNormalBias;
uniform float uViewBias;
uniform float uGamma;
uniform sampler2D uIrradianceAtlas;
uniform sampler2D uDistanceAtlas;

// Manual bilinear with texelFetch inside one probe tile: the same arithmetic as
// Atlas::bilinearInTile on the CPU (fractions from the tile-local coordinate).
vec4 ddgiBilinear(sampler2D atlas, ivec2 tileOrigin, int tileSize, vec2 local) {
    vec2 p = local - 0.5;
    vec2 f = floor(p);
    vec2 t = p - f;
    ivec2 i0 = tileOrigin + clamp(ivec2(f), ivec2(0), ivec2(tileSize - 2));
    vec4 a = mix(texelFetch(atlas, i0, 0), texelFetch(atlas, i0 + ivec2(1, 0), 0), t.x);
    vec4 b = mix(texelFetch(atlas, i0 + ivec2(0, 1), 0), texelFetch(atlas, i0 + ivec2(1, 1), 0), t.x);
    return mix(a, b, t.y);
}

float ddgiChebyshev(float r, float mean, float meanSquare) {
    if (r <= mean) return 1.0;
    float variance = max(meanSquare - mean * mean, 0.0);
    if (variance <= 0.0) return 0.0;
    float d = r - mean;
    float p = variance / (variance + d * d);
    return p * p * p;
}

float ddgiVolumeBlendWeight(int v, vec3 p) {
    vec3 x = (p - uOrigin[v]) / uSpacing[v];
    float w = 1.0;
    for (int a = 0; a < 3; ++a) {
        if (uCounts[v][a] < 2) continue;
        float last = float(uCounts[v][a] - 1);
        w *= clamp(x[a], 0.0, 1.0) * clamp(last - x[a], 0.0, 1.0);
    }
    return w;
}

vec3 ddgiSampleVolume(int v, vec3 p, vec3 n, vec3 toViewer) {
    ivec3 counts = uCounts[v];
    float minSpacing = min(uSpacing[v].x, min(uSpacing[v].y, uSpacing[v].z));
    vec3 q = p + (n * uNormalBias + toViewer * uViewBias) * minSpacing;
    vec3 rel = (q - uOrigin[v]) / uSpacing[v];
    ivec3 base = clamp(ivec3(floor(rel)), ivec3(0), max(counts - 2, ivec3(0)));
    vec3 alpha = clamp(rel - vec3(base), 0.0, 1.0);
    for (int a = 0; a < 3; ++a)
        if (counts[a] < 2) alpha[a] = 0.0;
    int tileI = uIrradianceTexels + 2, tileD = uDistanceTexels + 2;
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 stp = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        ivec3 logical = base + stp;
        if (any(greaterThanEqual(logical, counts))) continue;
        ivec3 s = ddgiPositiveMod(logical + uScroll[v], counts);
        int local = s.x + counts.x * (s.z + counts.z * s.y);
        vec4 data = probeData[uProbeBase[v] + local];
        if (data.w > 1.5) continue;  // off
        vec3 probePos = uOrigin[v] + vec3(logical) * uSpacing[v] + data.xyz;
        ivec2 tile = ivec2(s.x + counts.x * s.z, uTileRow[v] + s.y);

        vec3 toProbe = probePos - p;
        float toProbeLength = length(toProbe);
        vec3 dirToProbe = toProbeLength > 0.0 ? toProbe / toProbeLength : n;
        float wrap = 0.5 * (dot(dirToProbe, n) + 1.0);
        float w = wrap * wrap + 0.2;

        vec3 fromProbe = q - probePos;
        float r = length(fromProbe);
        vec3 dirFromProbe = r > 0.0 ? fromProbe / r : -n;
        vec4 moments = ddgiBilinear(uDistanceAtlas, tile * tileD, tileD, octTileCoordinate(dirFromProbe, uDistanceTexels));
        w *= ddgiChebyshev(r, moments.x, moments.y);
        w = max(w, 1e-6);
        const float crush = 0.2;
        if (w < crush) w *= w * w / (crush * crush);
        vec3 tri = mix(vec3(1.0) - alpha, alpha, vec3(stp));
        w *= tri.x * tri.y * tri.z;

        vec3 encoded = max(ddgiBilinear(uIrradianceAtlas, tile * tileI, tileI, octTileCoordinate(n, uIrradianceTexels)).rgb, vec3(0.0));
        sum += w * pow(encoded, vec3(0.5 * uGamma));
        wsum += w;
    }
    if (!(wsum > 0.0)) return vec3(0.0);
    vec3 e = sum / wsum;
    return e * e;
}

vec3 ddgiSampleIrradiance(vec3 p, vec3 n, vec3 toViewer) {
    if (uVolumeCount == 1) return ddgiSampleVolume(0, p, n, toViewer);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int v = 0; v < uVolumeCount && wsum < 1.0; ++v) {
        float w = v + 1 == uVolumeCount ? 1.0 : ddgiVolumeBlendWeight(v, p);
        w *= clamp(1.0 - wsum, 0.0, 1.0);
        if (w <= 0.0) continue;
        sum += w * ddgiSampleVolume(v, p, n, toViewer);
        wsum += w;
    }
    return wsum > 0.0 ? sum / wsum : vec3(0.0);
}
#endif
