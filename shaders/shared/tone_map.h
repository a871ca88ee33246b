// Display of linear HDR radiance, in C++ (PNG writer, metrics' 8-bit images) and GLSL (the
// viewer): exposure, a tone curve, then the sRGB transfer function. The same operations on both
// sides, so the screen shows what a screenshot's PNG holds.
//   kToneFilmic    Narkowicz's fit of the ACES filmic curve (2015), per channel (the default);
//   kToneReinhard  L / (1 + L) on luminance with the colour kept (seed 001's final pass).
#ifndef VOXGI_SHARED_TONE_MAP_H
#define VOXGI_SHARED_TONE_MAP_H

#include "color.h"
#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

constexpr int kToneFilmic = 0;
constexpr int kToneReinhard = 1;
// Middle grey: auto exposure maps the image's log-average luminance to it (Reinhard et al. 2002).
constexpr float kExposureKey = 0.18f;

inline float srgbEncode(float v) { return v <= 0.0031308f ? 12.92f * v : 1.055f * pow(v, 1.0f / 2.4f) - 0.055f; }

inline vec3 toneCurve(vec3 x, int curve) {
    if (curve == kToneReinhard) {
        float l = luminanceRec709(x);
        return l > 0.0f ? x / (1.0f + l) : vec3(0.0f);
    }
    return (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
}

// Linear radiance to 8-bit-ready sRGB in [0, 1]; exposureScale = 2^stops.
inline vec3 displaySrgb(vec3 linear, float exposureScale, int curve) {
    vec3 y = clamp(toneCurve(max(linear, vec3(0.0f)) * exposureScale, curve), vec3(0.0f), vec3(1.0f));
    return vec3(srgbEncode(y.x), srgbEncode(y.y), srgbEncode(y.z));
}

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
