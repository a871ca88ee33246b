// Points on a disc for screen-space kernels, the same in C++ and GLSL: Vogel's golden-angle
// spiral (n points spread evenly over the unit disc) turned by a per-pixel, per-frame angle from
// interleaved gradient noise (Jimenez 2014), so that kernels of few taps average out over pixels
// and accumulated frames. Used by the sun's soft shadows and image-space radiosity.
#ifndef VOXGI_SHARED_DISC_SAMPLES_H
#define VOXGI_SHARED_DISC_SAMPLES_H

#include "constants.h"
#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

// Point i of n on the unit disc, turned by `rotation` (radians).
inline vec2 vogelDisc(int i, int n, float rotation) {
    const float r = sqrt((float(i) + 0.5f) / float(n));
    const float theta = float(i) * 2.39996323f + rotation;
    return r * vec2(cos(theta), sin(theta));
}

// The kernel's turn at `pixel` in frame `frame`: interleaved gradient noise, moved on by the
// golden ratio each frame.
inline float discRotation(ivec2 pixel, int frame) {
    const float noise = fract(52.9829189f * fract(dot(vec2(pixel), vec2(0.06711056f, 0.00583715f))));
    return 2.0f * kPi * fract(noise + 0.61803399f * float(frame));
}

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
