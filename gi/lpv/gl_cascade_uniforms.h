// The uniforms of shaders/lpv/cascade_weights.glsl, for the programs that weigh light by
// cascade (injection and apply).
#pragma once

#include <vector>

#include "gi/lpv/cascades.h"
#include "gl/program.h"

namespace voxgi {

void setCascadeUniforms(const gl::Program& program, const std::vector<CascadePlacement>& cascades);

}  // namespace voxgi
