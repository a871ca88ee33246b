#include "gi/lpv/sky_bounce.h"

#include <cmath>

#include "gi/sky/sky_volume_texture.h"

namespace voxgi {

SkyBounceFace::SkyBounceFace(int size)
    : size_(size), program_(gl::Program::graphics("frame/fullscreen.vert", "lpv/sky_bounce.frag")), targets_(size) {
    face_.position = targets_.position.id();
    face_.normal = targets_.normal.id();
    face_.flux = targets_.flux.id();
    face_.albedo = targets_.albedo.id();
    face_.size = size;
    face_.orthographic = false;
    vao_ = gl::createVertexArray();
}

const RsmFace& SkyBounceFace::render(const GBufferView& g, const SkyVolumeTexture& sky) {
    glBindFramebuffer(GL_FRAMEBUFFER, targets_.fbo.id());
    glViewport(0, 0, size_, size_);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    program_.use();
    bindGBufferTextures(program_, g);
    sky.bind(program_, 4);
    // One texel covers (width / size) x (height / size) pixels of pixelEdge^2 each on the image
    // plane at unit distance.
    const float edge = pixelEdge(g);
    program_.set("uTexelSolidAngle", edge * edge * float(g.width) * float(g.height) / float(size_ * size_));
    program_.set("uEye", g.eye);
    program_.set("uForward", viewForward(g.viewProjection));
    program_.set("uSize", size_);
    glBindVertexArray(vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    // Surfels look back at the eye: readSurfels and the GL injector shift each VPL toward its
    // light, here toward the open side of the surface the camera sees.
    face_.origin = g.eye;
    return face_;
}

}  // namespace voxgi
