// Light propagation volumes as a frame technique: `lpv` (one volume around the scene) and
// `clpv` (camera-centred cascades). Per frame: reflective shadow maps -> light and blocker
// injection -> propagation (CPU reference or GL compute) -> deferred apply, each pass run when
// the plan (lpv_method.cpp) lists it. Nothing is redone while the lights, geometry and cascade
// placement stay the same.
#pragma once

#include <memory>

#include "gi/lpv/lpv_desc.h"
#include "gi/lpv/surfels.h"
#include "gi/technique.h"

namespace voxgi {

// Needs a current GL context; `desc` as read by readLpvDesc.
std::unique_ptr<GiTechnique> createLpvTechnique(const Scene& scene, const LpvDesc& desc, bool cascaded);

// The camera's blocker source on the CPU back end: the G-buffer read back and sampled as
// GBufferSampling (gi/lpv/gl_injection.h) says, each pixel a surfel of its footprint's area.
SurfelSource gbufferSurfels(const GBufferView& g, int target);

}  // namespace voxgi
