// Scene buffers shared by the frame passes; layouts match render/gl/gpu_layout.h.
#ifndef VOXGI_SCENE_DATA_GLSL
#define VOXGI_SCENE_DATA_GLSL
struct MaterialGpu {
    vec4 albedo;      // rgb, a unused
    vec4 emission;    // rgb, a unused
    float roughness;
    float metallic;
    float specular;
    int textureLayer; // -1 = none
};
layout(std430, binding = 0) readonly buffer Materials { MaterialGpu materials[]; };
layout(std430, binding = 1) readonly buffer TriangleMaterials { uint triangleMaterial[]; };
#endif
