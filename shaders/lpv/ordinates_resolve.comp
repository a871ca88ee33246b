#version 450 core
// The irradiance cube the apply pass reads (apply_ordinates.frag): each face's three axis
// groups (ordinates_sweep.comp) summed into the N x N x 6N texture, face f at z in [f N, (f+1) N).
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(std430, binding = 6) readonly buffer Irradiance { vec4 irradiance[]; };  // [axis][face][cell]
layout(rgba32f, binding = 0) uniform writeonly image3D uCube;

uniform int uN;

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    int n = uN;
    if (any(greaterThanEqual(c, ivec3(n)))) return;
    int cells = n * n * n, cell = (c.z * n + c.y) * n + c.x;
    for (int f = 0; f < 6; ++f) {
        vec4 e = vec4(0.0);
        for (int g = 0; g < 3; ++g) e += irradiance[(g * 6 + f) * cells + cell];
        imageStore(uCube, ivec3(c.x, c.y, f * n + c.z), vec4(e.rgb, 0.0));
    }
}
