// The scene uploaded for rasterization: one vertex buffer of world-space triangles, the
// per-triangle material ids, the material table and a texture array of albedo maps.
#pragma once

#include "gl/resources.h"
#include "scenes/scene.h"

namespace voxgi {

class SceneGpu {
public:
    explicit SceneGpu(const Scene& scene);

    // Binds materials (SSBO 0), triangle materials (SSBO 1) and the texture array.
    void bind(GLuint textureUnit) const;
    // Draws every triangle in one call (so gl_PrimitiveID is the global triangle index).
    void draw() const;

    std::size_t triangleCount() const { return triangles_; }
    static constexpr int kTextureSize = 512;  // albedo maps are resampled to this square size

private:
    gl::Handle vao_, vertices_, indices_, materials_, triangleMaterials_, textures_;
    std::size_t triangles_ = 0;
};

}  // namespace voxgi
