#version 450 core
// Instanced spheres (probes, light-volume cells) without a vertex buffer: a latitude-longitude
// mesh of kRings x kSegments quads from gl_VertexID.
#include "shared/constants.h"
struct Sphere {
    vec4 centerRadius;
    vec4 r;  // constant colour in .x of r, g, b, or 2-band SH per colour channel
    vec4 g;
    vec4 b;
};
layout(std430, binding = 1) readonly buffer Spheres { Sphere spheres[]; };
uniform mat4 uViewProjection;
out vec3 vNormal;
out vec3 vWorld;
flat out int vInstance;

const int kRings = 8;
const int kSegments = 12;

vec3 pointOn(int ring, int segment) {
    float theta = kPi * float(ring) / float(kRings);
    float phi = 2.0 * kPi * float(segment) / float(kSegments);
    return vec3(sin(theta) * cos(phi), cos(theta), sin(theta) * sin(phi));
}

void main() {
    int quad = gl_VertexID / 6;
    int corner = gl_VertexID % 6;
    int ring = quad / kSegments, segment = quad % kSegments;
    const ivec2 offsets[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
    vec3 n = pointOn(ring + offsets[corner].x, segment + offsets[corner].y);
    Sphere s = spheres[gl_InstanceID];
    vNormal = n;
    vInstance = gl_InstanceID;
    vWorld = s.centerRadius.xyz + s.centerRadius.w * n;
    gl_Position = uViewProjection * vec4(vWorld, 1.0);
}
