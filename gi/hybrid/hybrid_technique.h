// The hybrid method as a frame technique (`hybrid`, seed 002 chapter 6): the rasterized frame
// and a diffuse GI method (hybrid.diffuse), plus the mirror-like lobes traced with Embree on the
// CPU (gi/hybrid/mirror_paths.h). What the rays reach becomes layers of secondary G-buffers that
// the frame lights with its own passes (direct light and shadows, sky light, the diffuse
// method's light); composite() adds them to the pixels with their Fresnel weights.
#pragma once

#include <memory>

#include "gi/hybrid/hybrid_desc.h"
#include "gi/technique.h"

namespace voxgi {

// Needs a current GL context. `diffuse`: the technique of desc.diffuse, or null for none.
std::unique_ptr<GiTechnique> createHybridTechnique(const Scene& scene, const HybridDesc& desc,
                                                   std::unique_ptr<GiTechnique> diffuse);

}  // namespace voxgi
