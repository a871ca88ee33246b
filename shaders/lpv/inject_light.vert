#version 450 core
// One reflective-shadow-map texel (gl_VertexID in row-major texel order) as a VPL: the unit-flux
// cosine lobe about its normal times its flux, in the cell of the surfel shifted along its normal
// and toward the light (injectLight in gi/lpv/injection.cpp), times the VPL's share of cascade
// uLevel's ring or inner volume (gi/lpv/cascades.h). Outputs r, g, b SH.
#include "lpv/inject_common.glsl"
#include "lpv/cascade_weights.glsl"

uniform sampler2D uPosition;  // xyz, w = area
uniform sampler2D uNormal;    // xyz, w = 1 where a surface was hit
uniform sampler2D uFlux;
uniform int uSize;
uniform int uOrthographic;
uniform vec3 uLightOrigin;    // perspective maps
uniform vec3 uToLight;        // orthographic maps
uniform float uNormalShift;   // normalCells * h (computed in C++)
uniform float uLightShift;    // lightCells * h
uniform float uPi;
uniform int uShare;           // 0: all of it (one volume), 1: the ring share, 2: the inner share
uniform int uLevel;

void main() {
    ivec2 texel = ivec2(gl_VertexID % uSize, gl_VertexID / uSize);
    vec4 n4 = texelFetch(uNormal, texel, 0);
    vec3 flux = texelFetch(uFlux, texel, 0).rgb;
    if (!(n4.w > 0.0) || flux == vec3(0.0)) {
        dropPoint();
        return;
    }
    vec3 position = texelFetch(uPosition, texel, 0).xyz;
    vec3 n = n4.xyz;
    vec3 toLight = uOrthographic != 0 ? uToLight : normalizeExact(uLightOrigin - position);
    precise vec3 p = position + n * uNormalShift;
    p = p + toLight * uLightShift;
    precise vec3 scaled = p / uCellSize;
    ivec3 cell = ivec3(floor(scaled)) - uOrigin;
    float weight = 1.0;
    if (uShare != 0) {
        float outside = outsideFiner(uLevel, p);
        weight = uShare == 1 ? outside * cascadeInlier(uLevel, p) : 1.0 - outside;
    }
    if (!(weight > 0.0)) {
        dropPoint();
        return;
    }
    precise vec4 lobe = cosineLobeExact(n) / uPi;
    precise vec4 r = lobe * (flux.r * weight);
    precise vec4 g = lobe * (flux.g * weight);
    precise vec4 b = lobe * (flux.b * weight);
    emitPoint(cell, r, g, b);
}
