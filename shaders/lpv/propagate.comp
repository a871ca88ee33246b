#version 450 core
// One LPV propagation step on the GPU; the same math as gi/lpv/propagation.cpp (gatherCell),
// with the same precomputed face coefficients, so the two agree to float rounding.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform sampler3D uInR;
uniform sampler3D uInG;
uniform sampler3D uInB;
uniform sampler3D uFaceBlocker;  // every face's blocker and albedo (face_blockers.comp)
uniform sampler3D uFaceAlbedo;
layout(rgba32f, binding = 0) uniform writeonly image3D uOutR;
layout(rgba32f, binding = 1) uniform writeonly image3D uOutG;
layout(rgba32f, binding = 2) uniform writeonly image3D uOutB;
layout(rgba32f, binding = 3) uniform image3D uAccR;
layout(rgba32f, binding = 4) uniform image3D uAccG;
layout(rgba32f, binding = 5) uniform image3D uAccB;

uniform int uResolution;
uniform int uOcclusion;
uniform int uBounces;
uniform ivec3 uAxes[6];
uniform vec4 uFaceSample[30];  // [axis * 5 + face]: dOmega * Y(w_sf)
uniform vec4 uFaceBlock[30];   // Y(-w_sf)
uniform vec4 uFaceLobe[30];    // cosine lobe about the face normal / pi
uniform mat4 uUnoccluded[6];
const float FLUX_OF_Y00 = 3.5449077018110318;  // 4 pi Y00

// Unit-flux blocker lobe with band 1 limited to a clamped cosine's (see propagation.cpp).
vec4 reflectionShape(vec4 blocker, float flux) {
    vec4 shape = blocker / flux;
    float limit = 1.1547005 * shape.x, len = length(shape.yzw);
    if (len > limit) shape.yzw *= limit / len;
    return shape;
}

bool inside(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(uResolution))); }

// The face between `cell` and `cell + axis`: the mean of its 4 corner samples, computed for every
// face once per update (face_blockers.comp) rather than in every step.
void sharedFace(ivec3 cell, ivec3 axis, out vec4 blocker, out vec3 albedo) {
    ivec3 base = cell + max(axis, ivec3(0));
    int k = axis.x != 0 ? 0 : (axis.y != 0 ? 1 : 2);
    ivec3 at = ivec3(k * (uResolution + 1) + base.x, base.y, base.z);
    blocker = texelFetch(uFaceBlocker, at, 0);
    albedo = texelFetch(uFaceAlbedo, at, 0).rgb;
}

void main() {
    ivec3 d = ivec3(gl_GlobalInvocationID);
    if (!inside(d)) return;
    vec4 outR = vec4(0.0), outG = vec4(0.0), outB = vec4(0.0);
    for (int a = 0; a < 6; ++a) {
        ivec3 s = d - uAxes[a];
        if (!inside(s)) continue;
        vec4 r = texelFetch(uInR, s, 0), g = texelFetch(uInG, s, 0), b = texelFetch(uInB, s, 0);
        vec4 blocker = vec4(0.0);
        vec3 albedo;
        if (uOcclusion != 0) sharedFace(s, uAxes[a], blocker, albedo);
        if (blocker == vec4(0.0)) {
            outR += uUnoccluded[a] * r;
            outG += uUnoccluded[a] * g;
            outB += uUnoccluded[a] * b;
            continue;
        }
        for (int f = 0; f < 5; ++f) {
            int i = a * 5 + f;
            float pass = 1.0 - clamp(dot(blocker, uFaceBlock[i]), 0.0, 1.0);
            outR += (dot(r, uFaceSample[i]) * pass) * uFaceLobe[i];
            outG += (dot(g, uFaceSample[i]) * pass) * uFaceLobe[i];
            outB += (dot(b, uFaceSample[i]) * pass) * uFaceLobe[i];
        }
    }
    if (uOcclusion != 0 && uBounces != 0) {
        vec4 r = texelFetch(uInR, d, 0), g = texelFetch(uInG, d, 0), b = texelFetch(uInB, d, 0);
        for (int a = 0; a < 6; ++a) {
            vec4 blocker;
            vec3 albedo;
            sharedFace(d, uAxes[a], blocker, albedo);
            float flux = blocker.x * FLUX_OF_Y00;
            if (!(flux > 1e-12) || albedo == vec3(0.0)) continue;
            vec4 shape = reflectionShape(blocker, flux);
            vec3 reflected = vec3(0.0);
            for (int f = 0; f < 5; ++f) {
                int i = a * 5 + f;
                float beta = clamp(dot(blocker, uFaceBlock[i]), 0.0, 1.0);
                reflected += vec3(dot(r, uFaceSample[i]), dot(g, uFaceSample[i]), dot(b, uFaceSample[i])) * beta;
            }
            outR += (albedo.r * reflected.r) * shape;
            outG += (albedo.g * reflected.g) * shape;
            outB += (albedo.b * reflected.b) * shape;
        }
    }
    imageStore(uOutR, d, outR);
    imageStore(uOutG, d, outG);
    imageStore(uOutB, d, outB);
    imageStore(uAccR, d, imageLoad(uAccR, d) + outR);
    imageStore(uAccG, d, imageLoad(uAccG, d) + outG);
    imageStore(uAccB, d, imageLoad(uAccB, d) + outB);
}
