#version 450 core
// One sampled G-buffer pixel as a blocker (the camera's source; gbufferSurfels in
// gi/lpv/lpv_technique.cpp gives the CPU twin): its area is the pixel's footprint at its depth.
#include "lpv/inject_common.glsl"
#include "shared/gbuffer.h"

uniform sampler2D uPosition;  // the G-buffer (shaders/shared/gbuffer.h)
uniform sampler2D uNormal;
uniform sampler2D uAlbedo;
uniform sampler2D uEmission;
uniform int uStride;
uniform int uColumns;
uniform vec3 uEye;
uniform vec3 uForward;
uniform float uPixel;
uniform float uFullBlocker;   // 4 / 3
uniform float uFaceArea;      // h * h

void main() {
    ivec2 pixel = ivec2(gl_VertexID % uColumns, gl_VertexID / uColumns) * uStride + uStride / 2;
    vec4 p4 = texelFetch(uPosition, pixel, 0);
    if (!gbufferHit(p4)) {
        dropPoint();
        return;
    }
    vec3 n = normalizeExact(texelFetch(uNormal, pixel, 0).xyz);
    precise vec3 albedo = gbufferDiffuseAlbedo(p4, texelFetch(uAlbedo, pixel, 0), texelFetch(uEmission, pixel, 0));
    precise vec3 d = p4.xyz - uEye;
    precise float dist = sqrt(dotExact(d, d));
    precise vec3 w = d / dist;
    precise float c = max(dotExact(w, uForward), 1e-3);
    precise float solidAngle = uPixel * uPixel * c * c * c * float(uStride * uStride);
    precise float area = solidAngle * dist * dist / max(abs(dotExact(n, w)), 0.05);

    precise vec3 scaled = p4.xyz / uCellSize;
    scaled = scaled + 0.5;
    ivec3 corner = ivec3(floor(scaled)) - uOrigin;
    precise float coverage = area / uFaceArea;
    precise vec4 blocker = cosineLobeExact(n) * uFullBlocker;
    blocker = blocker * coverage;
    emitPoint(corner, blocker, vec4(albedo, 0.0), vec4(0.0));
}
