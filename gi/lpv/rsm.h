// Reflective shadow maps: the scene rasterized from each light, every texel a surfel with the
// diffuse flux it reflects (W). Directional lights use an orthographic map over the scene,
// spot lights a perspective one, point lights six 90-degree faces, quad lights the faces of a
// hemicube at their centre; every texel evaluates its light by shaders/shared/light_model.h.
#pragma once

#include <memory>
#include <vector>

#include <epoxy/gl.h>

#include "gi/lpv/surfels.h"
#include "gl/resources.h"
#include "scenes/scene.h"

namespace voxgi {

class SceneGpu;

// One rendered face, as GL textures (RGBA32F, size x size; see shaders/lpv/rsm.frag):
// position (w = surfel area), normal (w = 1 where a surface was hit), flux, albedo.
struct RsmFace {
    GLuint position = 0, normal = 0, flux = 0, albedo = 0;
    int size = 0;
    bool orthographic = false;   // a sun's map: every surfel's direction to the light is toLight
    glm::vec3 origin{0.0f};      // perspective maps: the light position the surfels look at
    glm::vec3 toLight{0.0f};     // orthographic maps: minus the light's travel direction
};

// The render targets of one face (and its depth buffer).
struct RsmTargets {
    gl::Handle fbo, position, normal, flux, albedo, depth;
    explicit RsmTargets(int size);
};

// How many faces the RSM renders for the scene's lights (a point light six, a sun or spot one, a
// quad light the faces of a hemicube about its normal).
std::size_t rsmFaceCount(const Scene& scene);

// The surfels of one face read back to the CPU, in texel order (row-major from texel 0).
SurfelSource readSurfels(const RsmFace& face);

class RsmRenderer {
public:
    explicit RsmRenderer(int size);
    ~RsmRenderer();
    RsmRenderer(const RsmRenderer&) = delete;
    RsmRenderer& operator=(const RsmRenderer&) = delete;

    // How many of the faces (rsmFaceCount, in light order) renderToTextures keeps at once:
    // textures of at most about 256 MB, at least one face (a 256^2 face takes 4.25 MB, a 4096^2
    // one 1.1 GB).
    std::size_t facesPerBatch() const;
    // Faces [first, first + count) of the scene's lights, kept on the GPU: the textures stay
    // valid until the next call. Needs a current GL context.
    const std::vector<RsmFace>& renderToTextures(const Scene& scene, const SceneGpu& gpu, std::size_t first,
                                                 std::size_t count);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace voxgi
