#version 450 core
// The blocker and albedo of every cell face, computed once per update before the propagation
// steps that read them (propagate.comp): the mean of the face's 4 corner samples, summed in the
// order the CPU's sharedFace sums them (gi/lpv/propagation.cpp), so the steps see the same
// floats as when each step averaged the corners itself. Faces of axis k sit at x offset
// k (N + 1) of the outputs; a face is named by its lowest corner.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D uBlocker;  // (N + 1)^3 corner samples
uniform sampler3D uAlbedo;
uniform int uResolution;
layout(rgba32f, binding = 0) uniform writeonly image3D uFaceBlocker;  // 3 (N + 1) x (N + 1) x (N + 1)
layout(rgba32f, binding = 1) uniform writeonly image3D uFaceAlbedo;

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    int corners = uResolution + 1;
    if (id.x >= 3 * corners || id.y >= corners || id.z >= corners) return;
    int k = id.x / corners;
    ivec3 base = ivec3(id.x - k * corners, id.y, id.z);
    int u = (k + 1) % 3, v = (k + 2) % 3;
    vec4 blocker = vec4(0.0);
    vec3 albedo = vec3(0.0);
    // A face reaching past the last corner bounds no cell: nothing reads it.
    if (base[u] < uResolution && base[v] < uResolution) {
        for (int du = 0; du < 2; ++du)
            for (int dv = 0; dv < 2; ++dv) {
                ivec3 c = base;
                c[u] += du;
                c[v] += dv;
                blocker += texelFetch(uBlocker, c, 0);
                albedo += texelFetch(uAlbedo, c, 0).rgb;
            }
        blocker *= 0.25;
        albedo *= 0.25;
    }
    imageStore(uFaceBlocker, id, blocker);
    imageStore(uFaceAlbedo, id, vec4(albedo, 0.0));
}
