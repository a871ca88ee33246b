// The sky-lighting volume (gi/sky/sky_volume.h) on the GPU, as deferred passes read it through
// shaders/common/sky_volume.glsl: its stored bricks in one 3D atlas texture (7 texels per cell
// along x) and an index texture of every brick's slot (-1: empty); the grid's placement is read
// from the volume it was made from.
// The frame renderer makes it once the volume is complete and hands it to the techniques
// (FrameInput::sky), so the sky_light pass and the LPV's sky bounce read the same texels.
#pragma once

#include "gl/resources.h"

namespace voxgi {

namespace gl {
class Program;
}
class SkyVolume;

class SkyVolumeTexture {
public:
    // Uploads every stored brick of `volume` (call once it is complete), which must outlive
    // this. Needs a current GL context; throws InputError naming sky.resolution when the atlas
    // exceeds the GPU's 3D texture size.
    explicit SkyVolumeTexture(const SkyVolume& volume);
    // Binds the atlas to `unit`, the index to `unit` + 1, and sets shaders/common/sky_volume.glsl's
    // uniforms in `program`.
    void bind(const gl::Program& program, int unit) const;
    // The CPU volume it was made from (techniques that sample on the CPU: DDGI's probe hits).
    const SkyVolume& volume() const { return volume_; }

private:
    const SkyVolume& volume_;
    gl::Handle atlas_, index_;
};

}  // namespace voxgi
