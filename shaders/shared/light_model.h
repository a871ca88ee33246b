// The one light model of voxgi: how a light reaches a receiving point, for every evaluator in
// C++ (DDGI probe-ray hits, the path tracer's delta lights) and GLSL (the direct light pass,
// reflective shadow maps).
//
// A light's emission (Light::emission, PackedLight::emission) is, by kind:
//   point        intensity I in W/sr, the same in every direction;
//   spot         intensity I in W/sr on its axis, times smoothstep(cos outer, cos inner, cos)
//                of the angle off the axis;
//   directional  irradiance E in W/m^2 on a surface facing it (the sun), arriving evenly from
//                the directions of a disc of angular radius alpha about its axis (alpha = 0:
//                one direction);
//   quad         radiance L in W/(m^2 sr), leaving the front face (the side of
//                cross(edgeU, edgeV)) only.
// Evaluators see a quad through one point q of it at a time (one per frame, ray or texel):
// as a point light at q of intensity L A cos(theta) about the quad normal, which averages over
// q in the quad to the area light. The path tracer samples quads as emissive triangles instead.
// They see a sun with a disc through one direction of it at a time, u = (0, 0) being the axis:
// each such direction delivers all of E, which averages over u to the disc (the cosine's change
// over a disc of the real sun's 0.27 degrees is below 1e-5).
#ifndef VOXGI_SHARED_LIGHT_MODEL_H
#define VOXGI_SHARED_LIGHT_MODEL_H

#include "constants.h"
#include "language.h"

#ifdef __cplusplus
namespace voxgi {
struct Light;
}
namespace voxgi::shading {
using namespace glm;
#endif

// PackedLight::kind.x; the values of LightType in scenes/scene.h.
constexpr int kLightPoint = 0;
constexpr int kLightSpot = 1;
constexpr int kLightDirectional = 2;
constexpr int kLightQuad = 3;

// One light as the GPU reads it (std430, 112 bytes), with what evaluation needs precomputed.
struct PackedLight {
    vec4 position;   // xyz: point and spot position, quad corner (m)
    vec4 direction;  // xyz: unit axis of the emission: the way spot and sun light travels, the
                     // quad's normal on its emitting side; zero for point lights
    vec4 emission;   // rgb: intensity, irradiance or radiance as listed above
    vec4 edgeU;      // xyz: quad edges (m), the quad is position + s edgeU + t edgeV, s, t in [0, 1]
    vec4 edgeV;
    vec4 shape;      // x, y: spot cos(outer), cos(inner half-angle); z: quad area (m^2);
                     // w: directional 1 - cos(alpha), the disc's angular radius alpha
    ivec4 kind;      // x: kLightPoint, kLightSpot, kLightDirectional or kLightQuad
};

// What one light delivers at a receiving point.
struct IncidentLight {
    vec3 direction;   // unit, from the receiver toward the light
    float distance;   // to the light point (m); +infinity for the sun, which no occluder is beyond
    vec3 irradiance;  // W/m^2 on a surface facing the light, before its cosine and visibility
    float falloff;    // irradiance over emission (the same for every channel); 0: no light
};

// Receivers this close to a light point (squared, m^2) get nothing: no direction is defined.
constexpr float kMinLightDistance2 = 1e-12f;

// The spot's angular falloff at cosine c off its axis. GLSL's smoothstep is undefined unless
// edge0 < edge1, so a cone without a soft band (inner angle >= outer) gets a hard edge at the
// outer angle.
inline float spotFalloff(float cosOuter, float cosInner, float c) {
    if (cosInner <= cosOuter) return c >= cosOuter ? 1.0f : 0.0f;
    return smoothstep(cosOuter, cosInner, c);
}

// A unit vector perpendicular to unit n.
inline vec3 perpendicularTo(vec3 n) {
    const vec3 a = abs(n.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    return normalize(cross(n, a));
}

// The direction of a cone of 1 - cos(half-angle) = oneMinusCos about unit `axis` that u in
// [0,1)^2 picks, uniform in solid angle; u.x = 0 is the axis. The sine comes from 1 - cos
// directly: for the sun's 0.27 degrees, cos is 1 - 1.1e-5, where float keeps two digits.
inline vec3 coneDirection(vec3 axis, float oneMinusCos, vec2 u) {
    const float h = u.x * oneMinusCos;  // 1 - cos(theta)
    const float sinTheta = sqrt(max(h * (2.0f - h), 0.0f));
    const float phi = 2.0f * kPi * u.y;
    const vec3 t = perpendicularTo(axis);
    const vec3 b = cross(axis, t);
    return normalize((1.0f - h) * axis + sinTheta * (cos(phi) * t + sin(phi) * b));
}

// Light `light` at receiver p; u in [0,1)^2 picks the point q on a quad light and the direction
// in a sun's disc (point and spot lights ignore it).
inline IncidentLight evaluateLight(PackedLight light, vec3 p, vec2 u) {
    IncidentLight incident;
    const int kind = light.kind.x;
    if (kind == kLightDirectional) {
        incident.direction = -vec3(light.direction);
        if (light.shape.w > 0.0f) incident.direction = -coneDirection(vec3(light.direction), light.shape.w, u);
        incident.distance = uintBitsToFloat(0x7f800000u);
        incident.falloff = 1.0f;
        incident.irradiance = vec3(light.emission);
        return incident;
    }
    vec3 at = vec3(light.position);
    if (kind == kLightQuad) at = at + u.x * vec3(light.edgeU) + u.y * vec3(light.edgeV);
    const vec3 toLight = at - p;
    const float d2 = dot(toLight, toLight);
    if (!(d2 > kMinLightDistance2)) {
        incident.direction = vec3(0.0f);
        incident.distance = 0.0f;
        incident.falloff = 0.0f;
        incident.irradiance = vec3(0.0f);
        return incident;
    }
    const float d = sqrt(d2);
    incident.direction = toLight / d;
    incident.distance = d;
    float intensity = 1.0f;  // toward p, over the emission
    if (kind == kLightSpot) {
        intensity = spotFalloff(light.shape.x, light.shape.y, dot(-incident.direction, vec3(light.direction)));
    } else if (kind == kLightQuad) {
        // The only place a quad's radiance becomes an intensity: L A cos(theta) at q.
        intensity = light.shape.z * max(dot(vec3(light.direction), -incident.direction), 0.0f);
    }
    incident.falloff = intensity / d2;
    incident.irradiance = vec3(light.emission) * incident.falloff;
    return incident;
}

// The radiance a ray from p along unit r meets on a quad light: its emission where the ray
// crosses the quad from its emitting side, else 0 (what a mirror at p reflects of it).
inline vec3 quadRadianceAlong(PackedLight light, vec3 p, vec3 r) {
    const vec3 n = vec3(light.direction);
    const float facing = dot(r, n);
    if (!(facing < 0.0f)) return vec3(0.0f);
    const float t = dot(vec3(light.position) - p, n) / facing;
    if (!(t > 0.0f)) return vec3(0.0f);
    // The hit in the quad's edge coordinates (a parallelogram: solve the 2 x 2 system).
    const vec3 q = p + t * r - vec3(light.position);
    const vec3 eu = vec3(light.edgeU), ev = vec3(light.edgeV);
    const float a = dot(eu, eu), b = dot(eu, ev), c = dot(ev, ev), d = dot(q, eu), e = dot(q, ev);
    const float det = a * c - b * b;
    if (!(det > 0.0f)) return vec3(0.0f);
    const float s = (c * d - b * e) / det, w = (a * e - b * d) / det;
    return s >= 0.0f && s <= 1.0f && w >= 0.0f && w <= 1.0f ? vec3(light.emission) : vec3(0.0f);
}

#ifdef __cplusplus
static_assert(sizeof(PackedLight) == 112, "std430 layout of PackedLight");

// `light` packed for evaluateLight: unit directions, the cone's cosines, the quad's normal and
// area (defined in scenes/light_model.cpp).
PackedLight packLight(const Light& light);
}  // namespace voxgi::shading
#endif

#endif
