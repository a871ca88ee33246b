#version 450 core
// Instanced voxel cubes without a vertex buffer: 36 vertices per cube from gl_VertexID.
struct Cube {
    vec4 centerHalf;  // xyz centre, w half size
    vec4 color;
};
layout(std430, binding = 0) readonly buffer Cubes { Cube cubes[]; };
uniform mat4 uViewProjection;
out vec3 vColor;

const vec3 kNormals[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));

void main() {
    int face = gl_VertexID / 6;
    int corner = gl_VertexID % 6;
    // Two triangles of the face as (s, t) in {-1, 1}^2.
    const vec2 st[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
    vec3 n = kNormals[face];
    vec3 u = abs(n.x) > 0.5 ? vec3(0, 1, 0) : vec3(1, 0, 0);
    vec3 v = cross(n, u);
    vec3 local = n + st[corner].x * u + st[corner].y * v;
    Cube c = cubes[gl_InstanceID];
    gl_Position = uViewProjection * vec4(c.centerHalf.xyz + c.centerHalf.w * local, 1.0);
    // Fixed shading per face so the cube shapes read without lights.
    float shade = 0.55 + 0.45 * abs(dot(n, normalize(vec3(0.4, 0.8, 0.45))));
    vColor = c.color.rgb * shade;
}
