#version 450 core
// One reflective-shadow-map texel as a blocker (injectBlockers in gi/lpv/injection.cpp): the
// cosine lobe scaled to reach 1 along n, times the covered fraction A_s / A_c of a cell face, at
// the nearest cell corner. Outputs the blocker SH and the albedo.
#include "lpv/inject_common.glsl"

uniform sampler2D uPosition;  // xyz, w = area
uniform sampler2D uNormal;    // xyz, w = 1 where a surface was hit
uniform sampler2D uAlbedo;
uniform int uSize;
uniform float uFullBlocker;   // 4 / 3
uniform float uFaceArea;      // h * h

void main() {
    ivec2 texel = ivec2(gl_VertexID % uSize, gl_VertexID / uSize);
    vec4 n4 = texelFetch(uNormal, texel, 0);
    if (!(n4.w > 0.0)) {
        dropPoint();
        return;
    }
    vec4 p4 = texelFetch(uPosition, texel, 0);
    precise vec3 scaled = p4.xyz / uCellSize;
    scaled = scaled + 0.5;
    ivec3 corner = ivec3(floor(scaled)) - uOrigin;
    precise float coverage = p4.w / uFaceArea;
    precise vec4 blocker = cosineLobeExact(n4.xyz) * uFullBlocker;
    blocker = blocker * coverage;
    emitPoint(corner, blocker, vec4(texelFetch(uAlbedo, texel, 0).rgb, 0.0), vec4(0.0));
}
