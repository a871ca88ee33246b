// The material model, identical to the path tracer's (gi/pathtrace/bsdf.h):
//   f = (1 - metallic)(1 - specular) albedo / pi  +  GGX(alpha = roughness^2, F0 = mix(specular, albedo, metallic))
// with Schlick Fresnel and the height-correlated Smith visibility term.
#ifndef VOXGI_BRDF_GLSL
#define VOXGI_BRDF_GLSL
#include "shared/constants.h"
#include "shared/material.h"

struct Surface {
    vec3 albedo;
    float roughness;
    float metallic;
    float specular;
    float transmission;  // the dielectric's share, not shaded here: the opaque lobes get 1 - it
};

float ggxD(float nh, float a2) {
    float d = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / max(kPi * d * d, 1e-12);
}

float smithVisibility(float nl, float nv, float a2) {
    float gv = nl * sqrt(nv * nv * (1.0 - a2) + a2);
    float gl = nv * sqrt(nl * nl * (1.0 - a2) + a2);
    return 0.5 / max(gv + gl, 1e-12);
}

vec3 fresnelSchlick(vec3 f0, float vh) {
    return f0 + (1.0 - f0) * pow(1.0 - clamp(vh, 0.0, 1.0), 5.0);
}

// BRDF value (without the cosine) for unit vectors n, v (to viewer) and l (to light).
vec3 evalBrdf(Surface s, vec3 n, vec3 v, vec3 l) {
    float nl = dot(n, l);
    float nv = dot(n, v);
    if (nl <= 0.0 || nv <= 0.0) return vec3(0.0);
    vec3 diffuse = diffuseAlbedo(s.albedo, s.metallic, s.specular, s.transmission) * kInvPi;
    vec3 f0 = mix(vec3(s.specular), s.albedo, s.metallic);
    if (max(f0.r, max(f0.g, f0.b)) <= 0.0) return diffuse;
    vec3 h = normalize(v + l);
    float alpha = max(s.roughness * s.roughness, kSmoothAlpha);
    float a2 = alpha * alpha;
    vec3 spec = fresnelSchlick(f0, dot(v, h)) * ggxD(max(dot(n, h), 0.0), a2) * smithVisibility(nl, nv, a2);
    return diffuse + (1.0 - s.transmission) * spec;
}
#endif
