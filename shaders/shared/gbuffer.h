// The G-buffer the frame renderer writes (shaders/frame/gbuffer.frag) and every deferred pass
// reads (direct light, GI apply, LPV camera blockers), as encode and decode of one surface:
//   position  RGBA32F  xyz world position (m), w = 1 + transmission where a surface was hit, 0 elsewhere
//   normal    RGBA16F  xyz shading normal turned toward the camera, w = roughness
//   albedo    RGBA16F  rgb albedo (texture applied), w = metallic
//   emission  RGBA32F  rgb emitted radiance of front faces (W/(m^2 sr)), w = specular
#ifndef VOXGI_SHARED_GBUFFER_H
#define VOXGI_SHARED_GBUFFER_H

#include "language.h"
#include "material.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

struct GBufferSurface {
    vec3 position;
    vec3 normal;      // unit
    vec3 albedo;
    vec3 emission;
    float roughness;
    float metallic;
    float specular;
    float transmission;  // the share of the dielectric lobe the rasterized passes do not shade
};

// One pixel's four texels, in the order of the targets above.
struct GBufferTexels {
    vec4 position;
    vec4 normal;
    vec4 albedo;
    vec4 emission;
};

inline GBufferTexels encodeGBuffer(GBufferSurface s) {
    GBufferTexels t;
    t.position = vec4(s.position, 1.0f + s.transmission);
    t.normal = vec4(s.normal, s.roughness);
    t.albedo = vec4(s.albedo, s.metallic);
    t.emission = vec4(s.emission, s.specular);
    return t;
}

inline bool gbufferHit(vec4 positionTexel) { return positionTexel.w > 0.0f; }

// The surface of a hit pixel; the normal is renormalized (it was stored at half precision).
inline GBufferSurface decodeGBuffer(GBufferTexels t) {
    GBufferSurface s;
    s.position = vec3(t.position);
    s.normal = normalize(vec3(t.normal));
    s.roughness = t.normal.w;
    s.albedo = vec3(t.albedo);
    s.metallic = t.albedo.w;
    s.emission = vec3(t.emission);
    s.specular = t.emission.w;
    s.transmission = max(t.position.w - 1.0f, 0.0f);
    return s;
}

inline vec3 surfaceDiffuseAlbedo(GBufferSurface s) {
    return diffuseAlbedo(s.albedo, s.metallic, s.specular, s.transmission);
}

// The diffuse albedo of a pixel from its position, albedo and emission texels alone, for passes
// that need nothing else.
inline vec3 gbufferDiffuseAlbedo(vec4 positionTexel, vec4 albedoTexel, vec4 emissionTexel) {
    return diffuseAlbedo(vec3(albedoTexel), albedoTexel.w, emissionTexel.w, max(positionTexel.w - 1.0f, 0.0f));
}

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
