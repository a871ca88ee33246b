// Where the cascades sit: `lpv` fits one volume around the scene; `clpv` centres nested
// volumes of doubling cell size on the camera (pushed ahead along the view), each snapped to
// multiples of its own cell size so the light does not swim as the camera moves.
//
// How the cascades share the light. A fine cascade holds only the light of the surfaces inside
// it, so reading it alone near a surface loses what arrives from farther away (the Cornell box
// seen from outside: the first cascades end a few centimetres into the box). The transport
// from a source s to a point p is therefore split by the finest cascade holding both: with
// f_L(x) the weight of cascade L at x (1 inside, 0 outside, linear across its border band) and
// S_L(x) = 1 - prod_{J <= L} (1 - f_J(x)) the share of x held by cascades 0..L,
//   - a VPL at s enters cascade L's "ring" volume with weight S_L(s) - S_{L-1}(s) and its
//     "inner" volume with weight S_{L-1}(s) (cascade 0 has no inner volume);
//   - a point p reads cascade L as S_L(p) x ring_L(p) + (S_L(p) - S_{L-1}(p)) x inner_L(p).
// Summed over L, every pair (s, p) is carried exactly once, by the cascade max(L(s), L(p)) in
// the limit of sharp borders: near light at the finest resolution that holds it, far light
// from the coarse cascades. One volume (`lpv`) has weight 1 everywhere inside it and reads as
// before. shaders/lpv/cascade_weights.glsl is the GPU twin.
#pragma once

#include <vector>

#include "gi/lpv/light_volume.h"
#include "gi/lpv/lpv_desc.h"
#include "scenes/scene.h"

namespace voxgi {

struct CascadePlacement {
    CascadeGrid grid;
    glm::vec3 fadeMin{0.0f};  // unsnapped bounds used for the border fade
    glm::vec3 fadeMax{0.0f};
    float fadeWidth = 0.0f;   // border band (m); 0 = no fade
};

// f_L(x): 1 inside the cascade, 0 outside its grid, linear across the border band.
float cascadeInlier(const CascadePlacement& cascade, glm::vec3 x);

// A VPL's weights in cascade `level` (see above): ring = S_L - S_{L-1}, inner = S_{L-1}.
struct SourceShares {
    float ring = 0.0f;
    float inner = 0.0f;
};
SourceShares sourceShares(const std::vector<CascadePlacement>& cascades, std::size_t level, glm::vec3 x);

// The finest cell edge: desc.cellSize, or fitted to the scene (lpv) / the view (clpv).
float finestCellSize(const LpvDesc& desc, const Bounds& sceneBounds, glm::vec3 eye);

std::vector<CascadePlacement> placeCascades(const LpvDesc& desc, const Bounds& sceneBounds, glm::vec3 eye,
                                            glm::vec3 viewDirection);

}  // namespace voxgi
