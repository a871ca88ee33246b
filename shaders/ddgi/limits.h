// DDGI's fixed sizes, one definition read by C++ (gi/ddgi) and GLSL (shaders/ddgi): valid in
// both languages.
#ifndef VOXGI_DDGI_LIMITS_H
#define VOXGI_DDGI_LIMITS_H
#ifdef __cplusplus
namespace voxgi {
#endif

// Probe volumes (cascades) the sampling shader takes as uniform arrays.
const int kDdgiMaxVolumes = 8;
// Rows of quad-light sample points the probe rays use (gi/ddgi/hit_shading.h, quadLightSamples).
const int kDdgiQuadSampleSets = 7;

#ifdef __cplusplus
}  // namespace voxgi
#endif
#endif
