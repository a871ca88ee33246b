#include "gi/lpv/gl_cascade_uniforms.h"

#include <string>

#include "shaders/lpv/limits.h"

namespace voxgi {

void setCascadeUniforms(const gl::Program& program, const std::vector<CascadePlacement>& cascades) {
    for (std::size_t c = 0; c < cascades.size() && c < std::size_t(kLpvMaxCascades); ++c) {
        const CascadePlacement& p = cascades[c];
        const std::string idx = "[" + std::to_string(c) + "]";
        program.set(("uLpvMin" + idx).c_str(), p.grid.worldMin());
        program.set(("uLpvMax" + idx).c_str(), p.grid.worldMax());
        program.set(("uLpvExtent" + idx).c_str(), p.grid.worldMax() - p.grid.worldMin());
        program.set(("uFadeMin" + idx).c_str(), p.fadeMin);
        program.set(("uFadeMax" + idx).c_str(), p.fadeMax);
        program.set(("uFadeWidth" + idx).c_str(), p.fadeWidth);
    }
}

}  // namespace voxgi
