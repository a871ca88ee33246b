// The sky's bounce in the light propagation volumes (seed 002 section 5.3.7; the sky issue's
// item 3): surfaces the camera sees, lit by the sky-lighting volume, become virtual point lights
// injected with the lights' own (shaders/lpv/sky_bounce.frag). One more reflective shadow map
// face, made from the G-buffer, so both back ends inject it as they inject a light's face.
// Surfaces off screen bounce no sky light (the seed's limitation, docs/sky.md).
#pragma once

#include "gi/lpv/rsm.h"
#include "gi/technique.h"
#include "gl/program.h"

namespace voxgi {

class SkyVolumeTexture;

class SkyBounceFace {
public:
    // A face of size^2 texels over the whole G-buffer. Needs a current GL context.
    explicit SkyBounceFace(int size);
    // The face for G-buffer `g`, lit by `sky`; valid until the next call.
    const RsmFace& render(const GBufferView& g, const SkyVolumeTexture& sky);

private:
    int size_;
    gl::Program program_;
    RsmTargets targets_;
    gl::Handle vao_;  // full-screen triangles need one bound, with no attributes
    RsmFace face_;
};

}  // namespace voxgi
