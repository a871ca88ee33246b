#version 450 core
// Places one injected point on its cell: layer = z, pixel = (x, y) of an N^2 (or (N+1)^2) viewport.
layout(points) in;
layout(points, max_vertices = 1) out;

uniform int uVolumeSize;

in Injected {
    flat int valid;
    flat ivec3 cell;
    flat vec4 value0;
    flat vec4 value1;
    flat vec4 value2;
} gIn[];

flat out vec4 fValue0;
flat out vec4 fValue1;
flat out vec4 fValue2;

void main() {
    if (gIn[0].valid == 0) return;
    ivec3 c = gIn[0].cell;
    gl_Position = vec4((vec2(c.xy) + 0.5) / float(uVolumeSize) * 2.0 - 1.0, 0.0, 1.0);
    gl_Layer = c.z;
    fValue0 = gIn[0].value0;
    fValue1 = gIn[0].value1;
    fValue2 = gIn[0].value2;
    EmitVertex();
    EndPrimitive();
}
