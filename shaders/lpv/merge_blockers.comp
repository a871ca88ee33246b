#version 450 core
// Merges one source's summed blockers into the geometry volume, per corner sample:
// mergeBlockers (gi/lpv/light_volume.cpp): the sum when the two face opposite ways (band-1
// vectors disagree), else the one with the larger peak (blockerPeak); albedo by max.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(rgba32f, binding = 0) uniform image3D uBlocker;
layout(rgba32f, binding = 1) uniform image3D uAlbedo;
uniform sampler3D uSourceBlocker;
uniform sampler3D uSourceAlbedo;
uniform int uSize;  // N + 1
uniform vec2 uShY;  // Y00, Y1 (gi/sh/sh.h)

float blockerPeak(vec4 b) {
    precise float band1 = b.y * b.y + b.z * b.z;
    band1 = band1 + b.w * b.w;
    precise float peak = b.x * uShY.x + sqrt(band1) * uShY.y;
    return peak;
}

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, ivec3(uSize)))) return;
    vec4 a = imageLoad(uBlocker, c), b = texelFetch(uSourceBlocker, c, 0);
    precise float facing = a.y * b.y + a.z * b.z;
    facing = facing + a.w * b.w;
    precise vec4 merged = facing < 0.0 ? a + b : (blockerPeak(b) > blockerPeak(a) ? b : a);
    imageStore(uBlocker, c, merged);
    imageStore(uAlbedo, c, max(imageLoad(uAlbedo, c), texelFetch(uSourceAlbedo, c, 0)));
}
