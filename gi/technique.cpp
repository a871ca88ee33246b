#include "gi/technique.h"

#include "gl/program.h"
#include "scenes/errors.h"

namespace voxgi {

void GiTechnique::dumpVdb(const std::string&) const {
    throw NotImplementedError("method '" + name() + "' has no .vdb dump yet");
}

void bindGBufferTextures(const gl::Program& program, const GBufferView& g) {
    const char* names[4] = {"uPosition", "uNormal", "uAlbedo", "uEmission"};
    const GLuint textures[4] = {g.position, g.normal, g.albedo, g.emission};
    for (int i = 0; i < 4; ++i) {
        glBindTextureUnit(GLuint(i), textures[i]);
        program.set(names[i], i);
    }
    program.set("uTracedRoughness", g.tracedRoughness);
}

DebugDrawing GiTechnique::debugView(const std::string&, const DebugViewContext&) const { return {}; }

}  // namespace voxgi
