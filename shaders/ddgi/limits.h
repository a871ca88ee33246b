// DDGI's fixed sizes, one definition read by C++ (gi/ddgi) and GLSL (shaders/ddgi): valid in
// both languages.
#ifndef VOXGI_DDGI_LIMITS_H
#define VOXGI_DDGI_LIMITS_H
#ifdef __cplusplus
namespace voxgi {
#endif

// Probe volumes (cascades) the sampling shader takes as uniform arrays.
const int kDdgiMaxVolumes = 8;

#ifdef __cplusplus
}  // namespace voxgi
#endif
#endif
