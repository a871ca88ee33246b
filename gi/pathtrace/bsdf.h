// The path tracer's material model at one surface point. The opaque part is the BRDF every
// voxgi renderer uses (shaders/common/brdf.glsl):
//   f = (1 - metallic)(1 - specular) albedo / pi + GGX(alpha = roughness^2, F0 = mix(specular, albedo, metallic))
// with Schlick Fresnel and the height-correlated Smith term, shaded two-sided. A material with
// transmission t mixes in (weight t) a dielectric of index `ior`: smooth (a delta pair of
// mirror reflection and refraction) when roughness^2 < kSmoothAlpha, otherwise the rough GGX
// dielectric of Walter et al. 2007. Transmitted light is tinted by the albedo.
#pragma once

#include <glm/glm.hpp>

#include "scenes/scene.h"
#include "shaders/shared/material.h"

namespace voxgi::pt {

using shading::kSmoothAlpha;  // the GLSL BRDF clamps alpha there too

struct BsdfSample {
    glm::vec3 direction{0.0f};
    glm::vec3 weight{0.0f};  // f |cos| / pdf, including the radiance scaling across an interface
    float pdf = 0.0f;        // solid angle; for a delta lobe the discrete probability
    float radianceScale = 1.0f;  // (n_wo / n_wi)^2 folded into weight by a refraction, else 1
    bool delta = false;
};

class Bsdf {
public:
    // `wo` points away from the surface (towards the previous vertex). `geometric` and
    // `shading` are the hit's unit normals as stored; `frontFace` says which side `wo` is on.
    Bsdf(const Material& material, glm::vec3 albedo, glm::vec3 wo, glm::vec3 geometric, glm::vec3 shading,
         bool frontFace);
    // The frame and lobes alone: only mayReflect and hasSmoothPart may be called until
    // setAlbedo gives it its albedo.
    Bsdf(const Material& material, glm::vec3 wo, glm::vec3 geometric, glm::vec3 shading, bool frontFace);

    // f |cos(n, wi)|, for next-event estimation; delta lobes give zero.
    glm::vec3 eval(glm::vec3 wi) const;
    float pdf(glm::vec3 wi) const;
    // Both at once, sharing the half vector and the distribution term.
    glm::vec3 evalPdf(glm::vec3 wi, float* pdf) const;
    // u in [0,1)^3. False when the sample carries no energy (below the horizon...).
    bool sample(glm::vec3 u, BsdfSample& out) const;
    // The opaque part's GGX lobe alone (metals and the coat; no diffuse, no transmission),
    // sampled in proportion to D(h)(n.h): out.weight = (1 - transmission) f_ggx cos / pdf_ggx,
    // out.pdf that lobe's own density. The hybrid method traces glossy reflections with it.
    bool sampleGlossy(glm::vec2 u, BsdfSample& out) const;
    // The same surface with another albedo (`material` the one it was built with): the path
    // tracer builds its BSDF before the albedo's texels arrive, to trace shadow rays meanwhile.
    void setAlbedo(const Material& material, glm::vec3 albedo);
    // True when eval can be non-zero somewhere (a light sample is worth tracing).
    bool hasSmoothPart() const { return opaqueWeight_ > 0.0f || roughTransmission(); }
    // False only where eval(wi) is zero whatever the albedo: what decides whether a shadow ray
    // towards wi is worth tracing before the albedo is known.
    bool mayReflect(glm::vec3 wi) const {
        if (roughTransmission()) return true;
        return opaqueWeight_ > 0.0f && glm::dot(n_, wi) > 0.0f && glm::dot(n_, wo_) > 0.0f;
    }
    // The same surface point seen from `wo` instead: light subpaths sample with wo pointing
    // back along the light, and MIS weights need the pdf of each sample's reverse.
    Bsdf seenFrom(glm::vec3 wo) const;
    glm::vec3 wo() const { return wo_; }
    // Normals oriented to the side of wo (two-sided shading).
    glm::vec3 shadingNormal() const { return n_; }
    glm::vec3 geometricNormal() const { return ng_; }
    // Whether the surface scatters diffusely (after setAlbedo).
    bool hasDiffuseLobe() const;
    // From here on the diffuse lobe alone (weighted 1 - transmission as before): no GGX, no
    // dielectric; a sample of what was dropped is absorbed. A path tracer without caustics
    // (PathTracerOptions::caustics). Before or after setAlbedo.
    void keepDiffuseLobeOnly();

private:
    void setSpecularProbability();
    bool roughTransmission() const { return transmission_ > 0.0f && !smoothDielectric_ && !diffuseOnly_; }
    glm::vec3 evalOpaque(glm::vec3 wi, float* pdf) const;
    glm::vec3 evalRoughDielectric(glm::vec3 wi, float* pdf) const;
    bool sampleOpaque(glm::vec3 u, BsdfSample& out) const;
    bool sampleDielectric(glm::vec3 u, BsdfSample& out) const;

    glm::vec3 wo_, n_, ng_, t_, b_;
    glm::vec3 diffuse_{0.0f}, f0_{0.0f}, albedo_{0.0f};  // set by setAlbedo
    float alpha_ = 1.0f;
    float specularProbability_ = 0.0f;
    float opaqueWeight_ = 1.0f;   // 1 - transmission
    float transmission_ = 0.0f;
    float eta_ = 1.0f;            // index on the wo side over the index on the other side
    bool smoothDielectric_ = false;
    bool diffuseOnly_ = false;
};

// Unit t and b completing unit n to a right-handed orthonormal frame.
void orthonormalBasis(glm::vec3 n, glm::vec3& t, glm::vec3& b);

// Schlick's Fresnel of the opaque GGX lobe (metals and the coat), cosine between the view and
// the half vector (brdf.glsl's fresnelSchlick).
glm::vec3 fresnelSchlick(glm::vec3 f0, float cosine);

// Fresnel reflectance of a dielectric interface for unpolarised light; eta = n_incident / n_transmitted.
float fresnelDielectric(float cosIncident, float eta);

}  // namespace voxgi::pt
