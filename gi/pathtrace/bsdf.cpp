#include "gi/pathtrace/bsdf.h"

#include <algorithm>
#include <cmath>

#include "shaders/shared/color.h"
#include "shaders/shared/constants.h"
#include "shaders/shared/material.h"

namespace voxgi::pt {

namespace {

using shading::luminanceRec709;

float ggxD(float nh, float a2) {
    float d = nh * nh * (a2 - 1.0f) + 1.0f;
    return a2 / std::max(shading::kPi * d * d, 1e-12f);
}

// Height-correlated Smith visibility G2 / (4 nl nv), as in brdf.glsl.
float smithVisibility(float nl, float nv, float a2) {
    float gv = nl * std::sqrt(nv * nv * (1.0f - a2) + a2);
    float gl = nv * std::sqrt(nl * nl * (1.0f - a2) + a2);
    return 0.5f / std::max(gv + gl, 1e-12f);
}

float smithLambda(float cosTheta, float a2) {
    float c2 = std::max(cosTheta * cosTheta, 1e-12f);
    return 0.5f * (-1.0f + std::sqrt(1.0f + a2 * (1.0f - c2) / c2));
}

}  // namespace

glm::vec3 fresnelSchlick(glm::vec3 f0, float vh) {
    float m = 1.0f - std::clamp(vh, 0.0f, 1.0f);
    float m5 = m * m * m * m * m;
    return f0 + (glm::vec3(1.0f) - f0) * m5;
}

float fresnelDielectric(float cosIncident, float eta) {
    cosIncident = std::clamp(cosIncident, 0.0f, 1.0f);
    float sin2t = eta * eta * (1.0f - cosIncident * cosIncident);
    if (sin2t >= 1.0f) return 1.0f;
    float cosT = std::sqrt(1.0f - sin2t);
    float rs = (eta * cosIncident - cosT) / (eta * cosIncident + cosT);
    float rp = (cosIncident - eta * cosT) / (cosIncident + eta * cosT);
    return 0.5f * (rs * rs + rp * rp);
}

void orthonormalBasis(glm::vec3 n, glm::vec3& t, glm::vec3& b) {
    // Without branches on the normal's sign (Duff et al. 2017).
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

Bsdf::Bsdf(const Material& m, glm::vec3 albedo, glm::vec3 wo, glm::vec3 geometric, glm::vec3 shading, bool frontFace)
    : Bsdf(m, wo, geometric, shading, frontFace) {
    setAlbedo(m, albedo);
}

Bsdf::Bsdf(const Material& m, glm::vec3 wo, glm::vec3 geometric, glm::vec3 shading, bool frontFace) : wo_(wo) {
    ng_ = glm::dot(geometric, wo) < 0.0f ? -geometric : geometric;
    // Two-sided shading like the rasterizer's G-buffer: the shading normal follows the side seen.
    n_ = glm::dot(shading, ng_) < 0.0f ? -shading : shading;
    orthonormalBasis(n_, t_, b_);

    transmission_ = std::clamp(m.transmission, 0.0f, 1.0f);
    opaqueWeight_ = 1.0f - transmission_;
    float r2 = m.roughness * m.roughness;
    alpha_ = std::max(r2, kSmoothAlpha);
    smoothDielectric_ = r2 < kSmoothAlpha;
    eta_ = frontFace ? 1.0f / m.ior : m.ior;
}

void Bsdf::setAlbedo(const Material& m, glm::vec3 albedo) {
    albedo_ = albedo;
    diffuse_ = shading::diffuseAlbedo(albedo, m.metallic, m.specular, 0.0f);  // opaqueWeight_ carries 1 - transmission
    f0_ = glm::mix(glm::vec3(m.specular), albedo, m.metallic);
    setSpecularProbability();
}

bool Bsdf::hasDiffuseLobe() const {
    return opaqueWeight_ > 0.0f && std::max(std::max(diffuse_.r, diffuse_.g), diffuse_.b) > 0.0f;
}

void Bsdf::keepDiffuseLobeOnly() {
    diffuseOnly_ = true;
    setSpecularProbability();
}

void Bsdf::setSpecularProbability() {
    float nv = std::max(glm::dot(n_, wo_), 0.0f);
    // Zero exactly when the GGX lobe is left out (evalOpaque and sampleOpaque skip it).
    float ws = std::max(std::max(f0_.r, f0_.g), f0_.b) > 0.0f && !diffuseOnly_ ? luminanceRec709(fresnelSchlick(f0_, nv)) : 0.0f;
    float wd = luminanceRec709(diffuse_);
    specularProbability_ = ws + wd > 0.0f ? ws / (ws + wd) : 0.0f;
}

Bsdf Bsdf::seenFrom(glm::vec3 wo) const {
    Bsdf other = *this;
    other.wo_ = wo;
    if (glm::dot(ng_, wo) < 0.0f) {  // the other side: normals and indices turn over
        other.ng_ = -ng_;
        other.n_ = -n_;
        other.eta_ = 1.0f / eta_;
        orthonormalBasis(other.n_, other.t_, other.b_);
    }
    other.setSpecularProbability();
    return other;
}

glm::vec3 Bsdf::evalOpaque(glm::vec3 wi, float* pdf) const {
    *pdf = 0.0f;
    float nl = glm::dot(n_, wi), nv = glm::dot(n_, wo_);
    // The shading normal alone decides what is above the surface (the convention every voxgi
    // renderer shares, docs/reference.md): light below the triangle's plane but above the
    // interpolated one counts, as in the rasterizer.
    if (nl <= 0.0f || nv <= 0.0f) return glm::vec3(0.0f);
    glm::vec3 f = diffuse_ * (1.0f / shading::kPi);
    *pdf = (1.0f - specularProbability_) * nl / shading::kPi;
    if (specularProbability_ > 0.0f) {  // non-zero exactly when F0 is and the lobe is kept
        glm::vec3 h = glm::normalize(wo_ + wi);
        float a2 = alpha_ * alpha_;
        float nh = std::max(glm::dot(n_, h), 0.0f), vh = glm::dot(wo_, h);
        float D = ggxD(nh, a2);
        f += fresnelSchlick(f0_, vh) * D * smithVisibility(nl, nv, a2);
        if (vh > 0.0f) *pdf += specularProbability_ * D * nh / (4.0f * vh);
    }
    return f * nl;
}

glm::vec3 Bsdf::evalRoughDielectric(glm::vec3 wi, float* pdf) const {
    *pdf = 0.0f;
    float cosO = glm::dot(n_, wo_), cosI = glm::dot(n_, wi);
    if (cosO <= 0.0f || cosI == 0.0f) return glm::vec3(0.0f);
    float a2 = alpha_ * alpha_;
    if (cosI > 0.0f) {
        if (glm::dot(ng_, wi) <= 0.0f) return glm::vec3(0.0f);
        glm::vec3 h = glm::normalize(wo_ + wi);
        float woh = glm::dot(wo_, h), nh = glm::dot(n_, h);
        if (woh <= 0.0f || nh <= 0.0f) return glm::vec3(0.0f);
        float F = fresnelDielectric(woh, eta_);
        float D = ggxD(nh, a2);
        float G = 1.0f / (1.0f + smithLambda(cosO, a2) + smithLambda(cosI, a2));
        *pdf = F * D * nh / (4.0f * woh);
        return glm::vec3(F * D * G / (4.0f * cosO));
    }
    if (glm::dot(ng_, wi) >= 0.0f) return glm::vec3(0.0f);
    // Indices relative to the far side: n(wo side) = eta_, n(wi side) = 1.
    glm::vec3 h = -(eta_ * wo_ + wi);
    float len = glm::length(h);
    if (len <= 0.0f) return glm::vec3(0.0f);
    h /= len;
    if (glm::dot(n_, h) < 0.0f) h = -h;
    float woh = glm::dot(wo_, h), wih = glm::dot(wi, h), nh = glm::dot(n_, h);
    if (woh <= 0.0f || wih >= 0.0f) return glm::vec3(0.0f);
    float denom = eta_ * woh + wih;
    denom *= denom;
    if (denom <= 0.0f) return glm::vec3(0.0f);
    float F = fresnelDielectric(woh, eta_);
    float D = ggxD(nh, a2);
    float G = 1.0f / (1.0f + smithLambda(cosO, a2) + smithLambda(cosI, a2));
    *pdf = (1.0f - F) * D * nh * std::abs(wih) / denom;
    // Walter et al.'s BTDF in radiance form (includes the eta^2 scaling) times |cos(n, wi)|.
    return albedo_ * (woh * std::abs(wih) * (1.0f - F) * D * G * eta_ * eta_ / (cosO * denom));
}

glm::vec3 Bsdf::evalPdf(glm::vec3 wi, float* pdf) const {
    glm::vec3 f(0.0f);
    *pdf = 0.0f;
    if (opaqueWeight_ > 0.0f) {
        float p;
        f += opaqueWeight_ * evalOpaque(wi, &p);
        *pdf += opaqueWeight_ * p;
    }
    if (roughTransmission()) {
        float p;
        f += transmission_ * evalRoughDielectric(wi, &p);
        *pdf += transmission_ * p;
    }
    return f;
}

glm::vec3 Bsdf::eval(glm::vec3 wi) const {
    float p;
    return evalPdf(wi, &p);
}

float Bsdf::pdf(glm::vec3 wi) const {
    float p;
    evalPdf(wi, &p);
    return p;
}

namespace {
// GGX normal distribution sampling proportional to D(h) (n.h), in the local frame.
glm::vec3 sampleGgxLocal(float u1, float u2, float a2) {
    float phi = 2.0f * shading::kPi * u1;
    float cos2 = (1.0f - u2) / (1.0f + (a2 - 1.0f) * u2);
    float cosT = std::sqrt(std::max(cos2, 0.0f));
    float sinT = std::sqrt(std::max(1.0f - cos2, 0.0f));
    return {sinT * std::cos(phi), sinT * std::sin(phi), cosT};
}
}  // namespace

bool Bsdf::sampleOpaque(glm::vec3 u, BsdfSample& out) const {
    if (glm::dot(n_, wo_) <= 0.0f) return false;
    glm::vec3 wi;
    if (u.z < specularProbability_) {
        glm::vec3 hl = sampleGgxLocal(u.x, u.y, alpha_ * alpha_);
        glm::vec3 h = hl.x * t_ + hl.y * b_ + hl.z * n_;
        wi = 2.0f * glm::dot(wo_, h) * h - wo_;
    } else {
        // Cosine-weighted hemisphere.
        float r = std::sqrt(u.x), phi = 2.0f * shading::kPi * u.y;
        float z = std::sqrt(std::max(0.0f, 1.0f - u.x));
        wi = r * std::cos(phi) * t_ + r * std::sin(phi) * b_ + z * n_;
    }
    out.direction = wi;
    return true;
}

bool Bsdf::sampleDielectric(glm::vec3 u, BsdfSample& out) const {
    float a2 = alpha_ * alpha_;
    glm::vec3 h = n_;
    if (!smoothDielectric_) {
        glm::vec3 hl = sampleGgxLocal(u.x, u.y, a2);
        h = hl.x * t_ + hl.y * b_ + hl.z * n_;
    }
    float woh = glm::dot(wo_, h);
    if (woh <= 0.0f) return false;
    float F = fresnelDielectric(woh, eta_);
    float choose = smoothDielectric_ ? u.x : u.z;
    if (choose < F) {
        out.direction = 2.0f * woh * h - wo_;
        if (smoothDielectric_) {
            out.weight = glm::vec3(1.0f);
            out.pdf = transmission_ * F;
        }
    } else {
        float sin2t = eta_ * eta_ * (1.0f - woh * woh);
        if (sin2t >= 1.0f) return false;
        float cosT = std::sqrt(1.0f - sin2t);
        out.direction = glm::normalize(-eta_ * wo_ + (eta_ * woh - cosT) * h);
        out.radianceScale = eta_ * eta_;
        if (smoothDielectric_) {
            // Radiance grows by (n_wo / n_wi)^2 = eta^2 when squeezed into the denser medium.
            out.weight = albedo_ * (eta_ * eta_);
            out.pdf = transmission_ * (1.0f - F);
        }
    }
    // With interpolated normals a direction can land on the wrong geometric side; following it
    // would cross the surface without paying the interface (a refraction weight without its
    // inverse), so such samples end the path: energy can be lost there, never gained.
    bool reflected = choose < F;
    if ((glm::dot(ng_, out.direction) > 0.0f) != reflected) return false;
    out.delta = smoothDielectric_;
    return true;
}

bool Bsdf::sampleGlossy(glm::vec2 u, BsdfSample& out) const {
    out = BsdfSample{};
    const float nv = glm::dot(n_, wo_);
    if (!(opaqueWeight_ > 0.0f) || !(specularProbability_ > 0.0f) || nv <= 0.0f) return false;
    const float a2 = alpha_ * alpha_;
    const glm::vec3 hl = sampleGgxLocal(u.x, u.y, a2);
    const glm::vec3 h = hl.x * t_ + hl.y * b_ + hl.z * n_;
    const float vh = glm::dot(wo_, h), nh = hl.z;
    const glm::vec3 wi = 2.0f * vh * h - wo_;
    const float nl = glm::dot(n_, wi);
    if (vh <= 0.0f || nl <= 0.0f || nh <= 0.0f || glm::dot(ng_, wi) <= 0.0f) return false;
    // f cos / pdf with pdf = D (n.h) / (4 v.h): D cancels.
    out.direction = wi;
    out.pdf = ggxD(nh, a2) * nh / (4.0f * vh);
    out.weight = opaqueWeight_ * fresnelSchlick(f0_, vh) * (smithVisibility(nl, nv, a2) * nl * 4.0f * vh / nh);
    return out.weight.r > 0.0f || out.weight.g > 0.0f || out.weight.b > 0.0f;
}

bool Bsdf::sample(glm::vec3 u, BsdfSample& out) const {
    out = BsdfSample{};
    bool ok;
    if (u.z < transmission_) {
        if (diffuseOnly_) return false;  // the dielectric's share, absorbed
        u.z /= transmission_;
        ok = sampleDielectric(u, out);
        if (ok && out.delta) return true;
    } else {
        u.z = opaqueWeight_ > 0.0f ? (u.z - transmission_) / opaqueWeight_ : 0.0f;
        ok = sampleOpaque(u, out);
    }
    if (!ok) return false;
    // Non-delta lobes: one-sample MIS over every lobe that could have produced this direction.
    glm::vec3 f = evalPdf(out.direction, &out.pdf);
    if (!(out.pdf > 0.0f)) return false;
    out.weight = f / out.pdf;
    return out.weight.r > 0.0f || out.weight.g > 0.0f || out.weight.b > 0.0f;
}

}  // namespace voxgi::pt
