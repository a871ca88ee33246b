#include "gi/ddgi/nano_geometry_gl.h"

#include "volumes/nano_geometry.h"

namespace voxgi {

NanoGeometryGl::NanoGeometryGl(const NanoGeometry& geometry)
    : buffer_(gl::createBuffer(geometry.bytes(), geometry.words.data(), 0)),
      normalGrid_(geometry.normalGrid),
      albedoGrid_(geometry.albedoGrid),
      offsetGrid_(geometry.offsetGrid),
      voxelSize_(geometry.voxelSize) {}

void NanoGeometryGl::bind(const gl::Program& program, GLuint binding) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer_.id());
    program.set("uNanoNormalGrid", unsigned(normalGrid_));
    program.set("uNanoAlbedoGrid", unsigned(albedoGrid_));
    program.set("uNanoOffsetGrid", unsigned(offsetGrid_));
    program.set("uNanoVoxelSize", voxelSize_);
}

}  // namespace voxgi
