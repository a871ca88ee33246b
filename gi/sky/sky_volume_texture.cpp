#include "gi/sky/sky_volume_texture.h"

#include <string>

#include "gi/sky/sky_volume.h"
#include "gl/program.h"
#include "scenes/errors.h"

namespace voxgi {

SkyVolumeTexture::SkyVolumeTexture(const SkyVolume& volume)
    : volume_(volume) {
    const glm::ivec3 atlas = volume.atlasSize(), bricks = volume.brickDims();
    GLint limit = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &limit);
    if (glm::max(atlas.x, glm::max(atlas.y, atlas.z)) > limit || glm::max(bricks.x, glm::max(bricks.y, bricks.z)) > limit)
        throw InputError("sky.resolution: the sky volume's " + std::to_string(volume.activeBricks()) +
                         " bricks need a " + std::to_string(atlas.x) + " x " + std::to_string(atlas.y) + " x " +
                         std::to_string(atlas.z) + " texture, beyond this GPU's " + std::to_string(limit));
    atlas_ = gl::createTexture(GL_TEXTURE_3D, GL_RGBA32F, atlas.x, atlas.y, atlas.z);
    glTextureSubImage3D(atlas_.id(), 0, 0, 0, 0, atlas.x, atlas.y, atlas.z, GL_RGBA, GL_FLOAT, volume.packed().data());
    index_ = gl::createTexture(GL_TEXTURE_3D, GL_R32I, bricks.x, bricks.y, bricks.z);
    glTextureParameteri(index_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(index_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureSubImage3D(index_.id(), 0, 0, 0, 0, bricks.x, bricks.y, bricks.z, GL_RED_INTEGER, GL_INT,
                        volume.brickSlots().data());
}

void SkyVolumeTexture::bind(const gl::Program& program, int unit) const {
    glBindTextureUnit(GLuint(unit), atlas_.id());
    glBindTextureUnit(GLuint(unit + 1), index_.id());
    program.set("uSkyVolume", unit);
    program.set("uSkyBricks", unit + 1);
    program.set("uSkyOrigin", volume_.origin());
    program.set("uSkyCellSize", volume_.cellSize());
    program.set("uSkyDims", volume_.dims());
    program.set("uSkyAtlasColumns", volume_.atlasColumns());
}

}  // namespace voxgi
