// Real SH, 2 bands, same order, signs and constants as gi/sh/sh.h (a test compares them).
#ifndef VOXGI_SH_GLSL
#define VOXGI_SH_GLSL
#include "shared/constants.h"
const float SH_Y00 = 0.282094791773878;
const float SH_Y1 = 0.488602511902920;
const float SH_COS_LOBE0 = kPi;
const float SH_COS_LOBE1 = 2.0943951023931954923;  // 2 pi / 3

vec4 shBasis(vec3 w) { return vec4(SH_Y00, -SH_Y1 * w.y, SH_Y1 * w.z, -SH_Y1 * w.x); }

float shEvaluate(vec4 f, vec3 w) { return dot(f, shBasis(w)); }

vec4 shCosineLobe(vec3 n) { return shBasis(n) * vec4(SH_COS_LOBE0, SH_COS_LOBE1, SH_COS_LOBE1, SH_COS_LOBE1); }

float shConvolveCosine(vec4 f, vec3 n) { return dot(f, shCosineLobe(n)); }
#endif
