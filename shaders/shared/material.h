// The material as the GPU reads it (SSBO 0 of gl/scene_gpu.cpp, declared in
// shaders/common/scene_data.glsl) and the one diffuse albedo of the material model
// (shaders/common/brdf.glsl, gi/pathtrace/bsdf.h):
//   f = (1 - transmission) [(1 - metallic)(1 - specular) albedo / pi + GGX(alpha = roughness^2, F0 = mix(specular, albedo, metallic))]
// plus, with weight transmission, a dielectric of index ior (the path tracer and the hybrid
// method trace it; the rasterized passes see only the opaque part).
#ifndef VOXGI_SHARED_MATERIAL_H
#define VOXGI_SHARED_MATERIAL_H

#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

// std430, 48 bytes.
struct MaterialGpu {
    vec4 albedo;       // rgb linear base colour, a transmission
    vec4 emission;     // rgb emitted radiance W/(m^2 sr), a unused
    float roughness;   // GGX perceptual roughness
    float metallic;
    float specular;    // F0 of the dielectric coat
    int textureLayer;  // layer of the albedo texture array; -1 = none
};

// Below this GGX alpha (roughness^2) a lobe is a mirror: the BRDF clamps alpha here, the path
// tracer's dielectrics become a delta pair of reflection and refraction, and the hybrid method
// traces these lobes instead of shading them from the lights (gi/hybrid/).
constexpr float kSmoothAlpha = 1e-3f;

inline bool smoothLobe(float roughness) { return roughness * roughness < kSmoothAlpha; }

// A material with a mirror-like lobe: smooth, with a coat, a metal or transmission.
inline bool hasMirrorLobe(float roughness, float metallic, float specular, float transmission) {
    return smoothLobe(roughness) && (transmission > 0.0f || metallic > 0.0f || specular > 0.0f);
}

// A glossy lobe the hybrid method traces (gi/hybrid/): the opaque part's GGX lobe of a coat or a
// metal, rougher than a mirror but no rougher than maxRoughness (perceptual roughness).
inline bool glossyLobe(float roughness, float metallic, float specular, float transmission, float maxRoughness) {
    return !smoothLobe(roughness) && roughness <= maxRoughness && transmission < 1.0f &&
           (metallic > 0.0f || specular > 0.0f);
}

// Whether rays trace this surface's reflection when the hybrid method traces lobes up to
// maxRoughness (< 0: nothing is traced; 0: mirror-like lobes only). The rasterized passes then
// leave its reflection of quad lights and its glossy indirect light to the rays.
inline bool tracedLobe(float roughness, float metallic, float specular, float transmission, float maxRoughness) {
    return maxRoughness >= 0.0f && (hasMirrorLobe(roughness, metallic, specular, transmission) ||
                                    glossyLobe(roughness, metallic, specular, transmission, maxRoughness));
}

// The albedo of the Lambert lobe: what a surface scatters diffusely, the rest going to the GGX
// lobe (metals and the dielectric coat's F0) and through the surface (transmission). Every
// diffuse bounce (probe-ray hits, RSM texels, LPV blockers, voxel albedo, the apply passes) uses this.
inline vec3 diffuseAlbedo(vec3 albedo, float metallic, float specular, float transmission) {
    return (1.0f - transmission) * (1.0f - metallic) * (1.0f - specular) * albedo;
}

#ifdef __cplusplus
static_assert(sizeof(MaterialGpu) == 48, "std430 layout of MaterialGpu");
}  // namespace voxgi::shading
#endif

#endif
