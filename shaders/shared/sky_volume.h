// The sky-lighting volume's lookup (gi/sky/sky_volume.h), for C++ (SkyVolume::sampleIrradiance)
// and GLSL (shaders/frame/sky_light.comp): a cell's 7 packed vec4 (27 irradiance SH
// coefficients, colour-major, and the validity), evaluated at a normal; and the cell and
// trilinear fractions around a point.
#ifndef VOXGI_SHARED_SKY_VOLUME_H
#define VOXGI_SHARED_SKY_VOLUME_H

#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

// The side of a brick, in cells: the sparse volume stores whole bricks (SkyVolume::kBrickCells).
constexpr int kSkyBrickCells = 4;

// Irradiance (the 9 pre-convolved coefficients per colour dotted with the 3-band basis at n;
// gi/sh/sh.h's order and signs). Negative ringing is clamped.
inline vec3 skyCellIrradiance(vec4 a, vec4 b, vec4 c, vec4 d, vec4 e, vec4 f, vec4 g, vec3 n) {
    float y[9];
    y[0] = 0.282094791773878f;
    y[1] = -0.488602511902920f * n.y;
    y[2] = 0.488602511902920f * n.z;
    y[3] = -0.488602511902920f * n.x;
    y[4] = 1.092548430592079f * n.x * n.y;
    y[5] = -1.092548430592079f * n.y * n.z;
    y[6] = 0.315391565252520f * (3.0f * n.z * n.z - 1.0f);
    y[7] = -1.092548430592079f * n.x * n.z;
    y[8] = 0.546274215296040f * (n.x * n.x - n.y * n.y);
    float r = a.x * y[0] + a.y * y[1] + a.z * y[2] + a.w * y[3] + b.x * y[4] + b.y * y[5] + b.z * y[6] + b.w * y[7] + c.x * y[8];
    float gr = c.y * y[0] + c.z * y[1] + c.w * y[2] + d.x * y[3] + d.y * y[4] + d.z * y[5] + d.w * y[6] + e.x * y[7] + e.y * y[8];
    float bl = e.z * y[0] + e.w * y[1] + f.x * y[2] + f.y * y[3] + f.z * y[4] + f.w * y[5] + g.x * y[6] + g.y * y[7] + g.z * y[8];
    return max(vec3(r, gr, bl), vec3(0.0f));
}

// The cell whose centre is the low corner of the 8 around p, and p's fraction between them.
struct SkyVolumeTaps {
    ivec3 base;
    vec3 fraction;
};

inline SkyVolumeTaps skyVolumeTaps(vec3 p, vec3 origin, float cellSize) {
    vec3 g = (p - origin) / cellSize;
    vec3 f = floor(g);
    SkyVolumeTaps t;
    t.base = ivec3(f);
    t.fraction = g - f;
    return t;
}

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
