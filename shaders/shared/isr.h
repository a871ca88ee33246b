// Image-space radiosity (seed 003) as C++ (gi/isr/isr_reference.cpp, the CPU reference) and
// GLSL (shaders/isr/) both compute it: what one screen patch sends to a receiving point, in
// physical units, and how the coarse result is upsampled.
//
// A patch is one coarse pixel: its surface point x, normal n_x, the radiance L_x the frame's
// direct light leaves it with, and its area, the pixel's footprint (its solid angle from the eye
// times distance^2 over the cosine to the view). It gives a receiver at p with normal n the
// irradiance of a small emitter (seed Eq. 6 times pi L_x):
//     dE = L_x cos(theta_p) cos(theta_x) A / (r^2 + A / pi)
// The A / pi in the denominator is a disc of area A seen on its axis: it bounds a patch right
// next to the receiver at pi L_x (a full hemisphere of it) where the seed's 1 / r^2 is unbounded.
// The seed's sphere occluder (Eq. 14) is the patch as a sphere of the same area: the fraction of
// the receiver's cosine-weighted hemisphere it hides, 2 (1 - cos alpha) cos(theta_p). With a far
// field the patch occludes as what it is, a flat disc: its form factor
//     F = cos(theta_p) |cos(theta_x)| A / (pi (r^2 + A / pi)),
// the same geometry as its light, so that a far field weighted by 1 - sum F fills exactly the
// directions the patches do not (a sphere hides a patch seen edge-on as much as one seen face on).
#ifndef VOXGI_SHARED_ISR_H
#define VOXGI_SHARED_ISR_H

#include "constants.h"
#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

// The footprint (m^2) of a pixel of solid angle `pixelSolidAngle` on the camera's axis, seen at
// x (normal nx) from `eye` looking along unit `forward`; grazing views are held at 1/20.
inline float isrPatchArea(vec3 x, vec3 nx, vec3 eye, vec3 forward, float pixelSolidAngle) {
    const vec3 d = x - eye;
    const float dist = length(d);
    const vec3 w = d / max(dist, 1e-30f);
    const float c = max(dot(w, forward), 1e-3f);
    return pixelSolidAngle * c * c * c * dist * dist / max(abs(dot(nx, w)), 0.05f);
}

// What the patch (x, nx, area, radiance) adds to the irradiance at p with normal n: the
// irradiance itself (rgb) and the occlusion its sphere (or, with `discs`, its disc) adds (w),
// both before the sampling weight.
inline vec4 isrPatchContribution(vec3 p, vec3 n, vec3 x, vec3 nx, float area, vec3 radiance, bool discs) {
    const vec3 d = x - p;
    const float r2 = dot(d, d);
    if (!(r2 > 0.0f)) return vec4(0.0f);
    const vec3 w = d / sqrt(r2);
    const float cosP = max(dot(n, w), 0.0f);
    const float facing = -dot(nx, w);  // cos(theta_x), negative for a patch's back
    const float bounded = area / (r2 + area * kInvPi);
    const vec3 e = radiance * (cosP * max(facing, 0.0f) * bounded);
    if (discs) return vec4(e, cosP * abs(facing) * bounded * kInvPi);  // a back hides as much
    const float sinAlpha2 = min(area * kInvPi / r2, 1.0f);  // (sphere radius / distance)^2
    const float occlusion = 2.0f * (1.0f - sqrt(1.0f - sinAlpha2)) * cosP;
    return vec4(e, occlusion);
}

// The upsampling weight of a coarse sample of view depth `coarseDepth` and normal `coarseNormal`
// for a pixel of depth `depth` and normal `normal`, with bilinear weight `bilinear` (seed Eq. 27,
// the depth term relative to the depth so that it holds at any scale, and a normal term).
inline float isrUpsampleWeight(float bilinear, float depth, float coarseDepth, vec3 normal, vec3 coarseNormal) {
    const float depthTerm = 1.0f / (0.01f + abs(depth - coarseDepth) / max(depth, 1e-30f));
    const float normalTerm = max(dot(normal, coarseNormal), 0.0f);
    return bilinear * depthTerm * normalTerm * normalTerm;
}

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
