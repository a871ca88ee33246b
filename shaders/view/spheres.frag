#version 450 core
// Sphere colour: constant (probe irradiance or state, already display values), or the light
// volume's 2-band SH evaluated toward the surface normal (a lobe painted on the sphere), scaled
// by uScale and tone-mapped like the frame.
#include "view/tone_map.glsl"
struct Sphere {
    vec4 centerRadius;
    vec4 r;
    vec4 g;
    vec4 b;
};
layout(std430, binding = 1) readonly buffer Spheres { Sphere spheres[]; };
uniform int uShMode;   // 0 constant, 1 SH
uniform float uScale;
// Hidden by the scene: the frame's G-buffer positions (w = 1 on a surface) over the viewport.
layout(binding = 0) uniform sampler2D uScenePosition;
uniform vec4 uViewport;  // x, y, w, h of the picture in the window
uniform vec3 uEye;
uniform int uOccludeByScene;
in vec3 vNormal;
in vec3 vWorld;
flat in int vInstance;
out vec4 outColor;

void main() {
    if (uOccludeByScene != 0) {
        vec4 surface = texture(uScenePosition, (gl_FragCoord.xy - uViewport.xy) / uViewport.zw);
        if (surface.w > 0.0 && distance(surface.xyz, uEye) < distance(vWorld, uEye)) discard;
    }
    Sphere s = spheres[vInstance];
    vec3 n = normalize(vNormal);
    if (uShMode == 0) {
        float shade = 0.6 + 0.4 * max(n.y, 0.0);
        outColor = vec4(vec3(s.r.x, s.g.x, s.b.x) * shade, 1.0);
        return;
    }
    // Basis order (Y00, Y1-1, Y10, Y11) as volumes/geometry_volume.h and gi/sh/sh.h.
    vec4 y = vec4(0.282094792, -0.488602512 * n.y, 0.488602512 * n.z, -0.488602512 * n.x);
    vec3 c = vec3(dot(s.r, y), dot(s.g, y), dot(s.b, y));
    outColor = vec4(toDisplay(c * uScale), 1.0);
}
