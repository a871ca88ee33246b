// The sky as every evaluator reads it, in C++ (path tracer, DDGI probe rays on the CPU) and
// GLSL (the background, DDGI probe rays on the GPU): a table of radiance (W/(m^2 sr)) over the
// equirectangular map of directions, read with bilinear interpolation. Atmosphere and
// environment-map skies are both tables (scenes/sky_model.h fills them); a constant sky is a
// single texel. Both languages find the same four texels and weights here and differ only in
// how they fetch them, so the sky the rasterizer shows is the sky the path tracer samples.
//
// Directions: theta = acos(d.y) from the zenith (+y), phi = atan(d.z, d.x) from +x toward +z;
// u = phi / (2 pi) in [0, 1), v = theta / pi, row 0 at the zenith. Texel (i, j) is centred on
// u = (i + 0.5) / width, v = (j + 0.5) / height; u wraps, v clamps.
#ifndef VOXGI_SHARED_SKY_H
#define VOXGI_SHARED_SKY_H

#include "language.h"
#include "constants.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

// atan for |x| <= 1: Abramowitz and Stegun's polynomial 4.4.49 (error below 2e-8 rad). The
// mapping uses it in both languages instead of their library acos and atan, which differ
// (llvmpipe's GLSL ones by up to about 1e-4 rad, a per cent of a texel's bilinear weight).
inline float skyAtanUnit(float x) {
    float x2 = x * x;
    return x * (1.0f + x2 * (-0.3333314528f + x2 * (0.1999355085f + x2 * (-0.1420889944f + x2 * (0.1065626393f +
                x2 * (-0.0752896400f + x2 * (0.0429096138f + x2 * (-0.0161657367f + x2 * 0.0028662257f))))))));
}

// atan2(y, x) in [-pi, pi] from skyAtanUnit; 0 at the origin (GLSL's atan(0, 0) is undefined).
inline float skyAtan2(float y, float x) {
    float ax = abs(x), ay = abs(y);
    if (ax == 0.0f && ay == 0.0f) return 0.0f;
    float a = ax >= ay ? skyAtanUnit(ay / ax) : 0.5f * kPi - skyAtanUnit(ax / ay);
    if (x < 0.0f) a = kPi - a;
    return y < 0.0f ? -a : a;
}

// The equirectangular coordinates of unit direction d.
inline vec2 skyUv(vec3 d) {
    float phi = skyAtan2(d.z, d.x);  // 0 at the poles, where the azimuth is undefined
    if (phi < 0.0f) phi += 2.0f * kPi;
    float u = phi * (0.5f / kPi);
    if (u >= 1.0f) u -= 1.0f;
    float y = clamp(d.y, -1.0f, 1.0f);
    return vec2(u, skyAtan2(sqrt(max(1.0f - y * y, 0.0f)), y) / kPi);
}

// The unit direction at equirectangular coordinates uv.
inline vec3 skyDirection(vec2 uv) {
    float phi = 2.0f * kPi * uv.x, theta = kPi * uv.y;
    float s = sin(theta);
    return vec3(s * cos(phi), cos(theta), s * sin(phi));
}

// The four texels around d and the bilinear weights between them: x0, x1 (columns, wrapped),
// y0, y1 (rows, clamped) and the fractions along x and y.
struct SkyTaps {
    ivec4 texels;  // x0, x1, y0, y1
    vec2 fraction;
};

inline SkyTaps skyTaps(vec3 d, int width, int height) {
    vec2 uv = skyUv(d);
    float x = uv.x * float(width) - 0.5f, y = uv.y * float(height) - 0.5f;
    float fx = floor(x), fy = floor(y);
    int x0 = int(fx), y0 = int(fy);
    SkyTaps t;
    t.fraction = vec2(x - fx, y - fy);
    int x1 = x0 + 1;
    if (x0 < 0) x0 += width;
    if (x1 >= width) x1 -= width;
    int y1 = min(y0 + 1, height - 1);
    y0 = max(y0, 0);
    t.texels = ivec4(x0, x1, y0, y1);
    return t;
}

// Bilinear blend of the texels (x0, y0), (x1, y0), (x0, y1), (x1, y1).
inline vec3 skyBlend(vec3 a, vec3 b, vec3 c, vec3 d, vec2 f) {
    return (a * (1.0f - f.x) + b * f.x) * (1.0f - f.y) + (c * (1.0f - f.x) + d * f.x) * f.y;
}

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
