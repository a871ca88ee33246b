// How a receiver facing n reads a cell's irradiance cube (lpv.transport=ordinates: the irradiance
// on the six axis normals, E+a and E-a, gi/lpv/ordinates.h): E(n) = sum over the axes a of
// towards_a x E+a + against_a x E-a. One definition for the apply pass
// (shaders/lpv/apply_ordinates.frag) and the C++ tests.
//
// - ambient cube (`lpv.cube_read=ambient`, lpv's default): the three faces n points along, by n_a^2;
// - quadratic (`lpv.cube_read=quadratic`, clpv's default): the quadratic in n that takes the six
//   values on the axis normals, sum over a of n_a^2 (E+a + E-a) / 2 + n_a (E+a - E-a) / 2. Radiance convolved
//   with the cosine and cut to three SH bands is such a quadratic; the six faces fix its band 0,
//   band 1 and band 2's diagonal, and its off-diagonal band-2 terms (which no axis face sees) are
//   taken as zero. Both read the faces exactly on the axis normals and a uniform field exactly
//   everywhere; for a tilted normal the quadratic is the closer one (docs/lpv.md, "Reading a
//   cell's light").
#ifndef VOXGI_SHARED_IRRADIANCE_CUBE_H
#define VOXGI_SHARED_IRRADIANCE_CUBE_H

#include "language.h"

#ifdef __cplusplus
namespace voxgi::shading {
using namespace glm;
#endif

struct CubeWeights {
    vec3 towards;  // per axis a, the weight of face +a (face 2a of the cube)
    vec3 against;  // the weight of face -a (face 2a + 1)
};

inline CubeWeights cubeWeights(vec3 n, bool quadratic) {
    CubeWeights w;
    if (quadratic) {
        w.towards = 0.5f * n * (n + 1.0f);
        w.against = 0.5f * n * (n - 1.0f);
    } else {
        vec3 squared = n * n;
        w.towards = mix(vec3(0.0f), squared, greaterThanEqual(n, vec3(0.0f)));
        w.against = squared - w.towards;
    }
    return w;
}

#ifdef __cplusplus
}  // namespace voxgi::shading
#endif

#endif
