// The LPV's fixed sizes, one definition read by C++ (gi/lpv) and GLSL (shaders/lpv): valid in
// both languages.
#ifndef VOXGI_LPV_LIMITS_H
#define VOXGI_LPV_LIMITS_H
#ifdef __cplusplus
namespace voxgi {
#endif

// Cascades per light volume: the apply pass binds three 3D textures per cascade for its ring
// light and three for its inner light (none for cascade 0, gi/lpv/cascades.h): 5 x 3 + 4 x 3 +
// the G-buffer's 4 = 31 stay under GL 4.5's guaranteed 32 fragment texture units.
const int kLpvMaxCascades = 5;

#ifdef __cplusplus
}  // namespace voxgi
#endif
#endif
