// Which faces a move of the directional LPV transport crosses, and what a cell's surfaces stop of
// it: one definition for the cpu sweeps (gi/lpv/ordinates.cpp) and the gl ones
// (shaders/lpv/ordinates_sweep.comp), which must agree to float rounding.
//
// A bin swept along `axis` lands its light through four taps j: each crosses the slab face, tap
// bits 0 and 1 also the side faces of axes u = (axis + 1) % 3 and v = (axis + 2) % 3. Vectors of
// the results hold (slab axis, u, v), in that order.
#ifndef VOXGI_SHARED_ORDINATE_TAPS_H
#define VOXGI_SHARED_ORDINATE_TAPS_H

#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

// perAxis's values for the axes tap j crosses, zero for the others.
inline vec3 crossedBy(int j, vec3 perAxis, int axis, int u, int v) {
    return vec3(perAxis[axis], (j & 1) != 0 ? perAxis[u] : 0.0f, (j & 2) != 0 ? perAxis[v] : 0.0f);
}

// What stops tap j's move into a cell, per crossed axis (gi/lpv/ordinates.h): the surfaces of one
// orientation |m_a| on every crossed axis, and the mean over the crossed axes of the shadow
// (P_a - |m_a|) / 2 of the surfaces whose normals cancel.
inline vec3 enteringStop(int j, vec3 absVectorCoverage, vec3 clutterShadow, int axis, int u, int v) {
    const float crossed = 1.0f + float(j & 1) + float((j >> 1) & 1);
    return crossedBy(j, absVectorCoverage, axis, u, v) + crossedBy(j, clutterShadow, axis, u, v) * (1.0f / crossed);
}

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
