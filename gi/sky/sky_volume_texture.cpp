#include "gi/sky/sky_volume_texture.h"

#include "gi/sky/sky_volume.h"
#include "gl/program.h"

namespace voxgi {

SkyVolumeTexture::SkyVolumeTexture(const SkyVolume& volume)
    : origin_(volume.origin()), cellSize_(volume.cellSize()), dims_(volume.dims()) {
    const int columns = SkyVolume::kVec4PerCell * dims_.x;
    texture_ = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, columns, dims_.y, dims_.z);
    glTextureSubImage3D(texture_.id(), 0, 0, 0, 0, columns, dims_.y, dims_.z, GL_RGBA, GL_FLOAT, volume.packed().data());
}

void SkyVolumeTexture::bind(const gl::Program& program, int unit) const {
    glBindTextureUnit(GLuint(unit), texture_.id());
    program.set("uSkyVolume", unit);
    program.set("uSkyOrigin", origin_);
    program.set("uSkyCellSize", cellSize_);
    program.set("uSkyDims", dims_);
}

}  // namespace voxgi
