// The scene uploaded for rasterization: one vertex buffer of world-space triangles, the
// per-triangle material ids, the material table, a texture array of albedo maps and the lights.
// Buffer layouts: shaders/shared/material.h and light_model.h; bindings as declared in
// shaders/common/scene_data.glsl.
#pragma once

#include <vector>

#include "gl/resources.h"
#include "scenes/scene.h"
#include "shaders/shared/light_model.h"

namespace voxgi {

// The sky's radiance table as an RGBA32F texture (shaders/shared/sky.h; 1 x 1 for a constant
// or no sky), read through shaders/common/sky.glsl.
gl::Handle uploadSkyTexture(const Sky& sky);

class SceneGpu {
public:
    explicit SceneGpu(const Scene& scene);

    // Binds materials (SSBO 0), triangle materials (SSBO 1), the lights and the texture array.
    void bind(GLuint textureUnit) const;
    // Binds the packed lights alone (SSBO 2), for passes whose texture units are their own.
    void bindLights() const;
    // Uploads `lights` packed when they differ from the last upload (the viewer moves the
    // scene's lights between frames); the frame renderer calls it once per frame.
    void updateLights(const std::vector<Light>& lights);
    // Draws every triangle in one call (so gl_PrimitiveID is the global triangle index).
    void draw() const;

    std::size_t triangleCount() const { return triangles_; }
    // The sky's table (uploadSkyTexture), and its upload again when the sky changed (followSun).
    GLuint skyTexture() const { return sky_.id(); }
    void updateSky(const Sky& sky) { sky_ = uploadSkyTexture(sky); }
    static constexpr int kTextureSize = 512;  // albedo maps are resampled to this square size

private:
    gl::Handle vao_, vertices_, indices_, materials_, triangleMaterials_, textures_;
    std::size_t triangles_ = 0;
    std::vector<shading::PackedLight> packedLights_;  // what updateLights last uploaded
    gl::Handle lights_;
    gl::Handle sky_;
};

}  // namespace voxgi
