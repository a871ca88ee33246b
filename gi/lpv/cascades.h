// Where the cascades sit: `lpv` fits one volume around the scene; `clpv` centres nested
// volumes of doubling cell size on the camera (pushed ahead along the view), each snapped to
// multiples of its own cell size so the light does not swim as the camera moves.
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
};

// The finest cell edge: desc.cellSize, or fitted to the scene (lpv) / the view (clpv).
float finestCellSize(const LpvDesc& desc, const Bounds& sceneBounds, glm::vec3 eye);

std::vector<CascadePlacement> placeCascades(const LpvDesc& desc, const Bounds& sceneBounds, glm::vec3 eye,
                                            glm::vec3 viewDirection);

}  // namespace voxgi
